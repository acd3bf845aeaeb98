"""A griffe extension for the API reference: a name in a package's ``__all__`` that the package
provides lazily (``unitopia_widget.UnitoPia``, imported on first use by the module's
``__getattr__``) becomes an alias of the one object of that name defined inside the package,
wherever it lives, so the reference names it through the top-level package."""
from __future__ import annotations

from griffe import Alias, Extension


def _definitions(module, name):
    for member in module.members.values():
        if member.is_alias:
            continue
        if member.is_module:
            yield from _definitions(member, name)
        elif member.name == name:
            yield member


class LazyExports(Extension):
    def on_package(self, *, pkg, **kwargs) -> None:
        for name in pkg.exports or ():
            if name in pkg.members:
                continue
            found = list(_definitions(pkg, name))
            if len(found) != 1:
                raise ValueError(f"__all__ names {name!r}: {len(found)} definitions in {pkg.path}")
            pkg.set_member(name, Alias(name, found[0], parent=pkg))
