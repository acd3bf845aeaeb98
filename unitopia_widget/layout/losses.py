"""Image-space losses on the coverage raster, with a hand-written backward.

Every layer has its own coverage slab ``C[a]`` (the sum of its marks' footprint
alphas per raster pixel). A layer ``a`` that blocks on layers ``b`` sees their
coverage as obstacles ``O[a] = sum_b C[b]`` with gradients stopped: one-way
blocking (paper section 4.1.2). Layers that share a container and do not
block each other see each other both ways, so they collide as one layer.

Strata (``strata.py``): a layer pulled by forces rests on the layers it blocks
on, as sediment does. Its obstacle is then ``min(sum_b C[b], 1)`` swept along
its force: down the raster axis nearest a directional force (everything below
the other layers' upper envelope, for a downward force), or radially in to a
point force (everything inside their outer envelope around the point), so its
marks cannot sift into the gaps between larger marks. Layers pulled by both
kinds of force, or by none, see the ink itself. With ``T = C + O``, per raster
pixel:

* overlap     ``relu(T - 1)``                 (paper eq. 3 with tau = 1 on coverage)
* containment ``alpha * field``               (a signed-distance penalty, eq. 4 improved)
* fill        ``inside * relu(1 - T)``        (closed boundaries only; the gap left open)

All terms are divided by ``terms.norm`` (the marks' footprint area, held
constant during a phase) so the loss reads as a fraction of the marks' area.
The samples are scattered into the slabs once; every term and the per-pixel
gradient are then dense, contiguous passes over the ``(L, S)`` slabs (the
raster is capped in size), and the backward gathers the pixel gradient at the
sample indices: one scatter and one gather of ``M`` samples per iteration,
with no autograd through the canvas. Nothing is read back to the host: the
per-layer sums stay on the device (``terms.sums``) for the solver to fetch.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import torch

from .strata import RadialShadow, shadow


@dataclass
class CanvasTerms:
    """Fixed inputs of the canvas loss. Shapes: ``L`` layers, ``S`` raster pixels."""

    penalty: torch.Tensor      # (L, S) containment cost per unit alpha, 0 inside
    outside: torch.Tensor      # (L, S) share of each pixel outside the allowed region
    inside: torch.Tensor       # (L, S) fill target: container coverage on closed layers, 0 on open ones
    blocks: torch.Tensor       # (L, L) float, blocks[a, b] = 1 when layer a treats b's ink as obstacle
    #: (L, L) float, rests[a, b] = 1 when layer a rests on b: b's ink swept along ``sweeps[a]``
    rests: torch.Tensor | None = None
    #: per layer: (raster dim 0 rows / 1 columns, reversed), a ``strata.RadialShadow`` or None
    sweeps: tuple = ()
    shape: tuple = ()          # (H, W) raster pixels: the slabs' image shape
    norm: float = 1.0          # the marks' total footprint area in raster px^2, a constant normaliser
    w_overlap: float = 1.0
    w_contain: float = 1.0
    w_fill: float = 0.0
    #: set by each forward: per-layer sums ``(4, L)`` on the device (overlap, outside,
    #: drawn alpha, covered container), in raster px^2
    sums: torch.Tensor | None = None
    _cover: torch.Tensor | None = None         # (L * S,) coverage buffer, all zeros between calls
    _tables: tuple | None = None               # fixed per-pixel tables, see ``tables``

    @functools.cached_property
    def inside_total(self) -> float:
        """The fill target's area in raster px^2 (closed layers)."""
        return float(self.inside.sum())

    @functools.cached_property
    def inside_host(self):
        """The fill target ``(L, S)`` as a host numpy array (copied from the device once)."""
        return self.inside.cpu().numpy()

    @functools.cached_property
    def any_blocks(self) -> bool:
        """Whether some layer sees another's ink itself (read once: the blocks are fixed)."""
        return bool(self.blocks.any())

    @functools.cached_property
    def has_obstacles(self) -> bool:
        """Whether some layer blocks on another (read once: the blocks are fixed)."""
        return self.any_blocks or (self.rests is not None and bool(self.rests.any()))

    def obstacles(self, own: torch.Tensor) -> torch.Tensor:
        """``O (L, S)`` from the coverage ``own (L, S)``: the ink of the layers each blocks
        on, and the shadow of those it rests on (see the module docstring)."""
        # blocks is all zeros where every layer rests (a stack): skip its product
        obstacle = self.blocks.to(own) @ own if self.any_blocks else torch.zeros_like(own)
        if self.rests is None:
            return obstacle
        resting = (self.rests.to(own) @ own).clamp_(max=1.0)
        for a, sweep in enumerate(self.sweeps):
            if sweep is not None and bool(self.rests[a].any()):
                obstacle[a] += self.swept(sweep, resting[a])
        return obstacle

    def obstacle(self, own: torch.Tensor, a: int) -> torch.Tensor:
        """``(S,)`` row ``a`` of ``obstacles(own)``, computed alone (one sweep, not ``L``)."""
        obstacle = self.blocks[a].to(own) @ own if self.any_blocks else torch.zeros_like(own[a])
        sweep = self.sweeps[a] if self.sweeps else None
        if self.rests is not None and sweep is not None and bool(self.rests[a].any()):
            obstacle = obstacle + self.swept(sweep, (self.rests[a].to(own) @ own).clamp_(max=1.0))
        return obstacle

    def swept(self, sweep, ink: torch.Tensor) -> torch.Tensor:
        """``(S,)`` the flat ``ink (S,)`` swept along ``sweep`` (see ``sweeps``)."""
        ink = ink.view(self.shape)
        return (sweep(ink) if isinstance(sweep, RadialShadow) else shadow(ink, *sweep)).reshape(-1)

    def coverage(self, values: torch.Tensor, index: torch.Tensor, owner: torch.Tensor,
                 layer: torch.Tensor):
        """``(flat (M,), own (L, S))``: each sample's index into the stacked slabs, and each
        layer's coverage; ``values``, ``index``, ``owner`` ``(M,)`` as from
        ``render_samples``, ``layer (N,)`` each unit's layer (long)."""
        n_layers, size = self.penalty.shape
        flat = index.long() + layer[owner] * size
        own = torch.zeros(n_layers * size, dtype=values.dtype, device=values.device) \
            .index_add_(0, flat, values).view(n_layers, size)
        return flat, own

    def unit_overlap(self, values: torch.Tensor, index: torch.Tensor, owner: torch.Tensor,
                     layer: torch.Tensor, n_units: int) -> torch.Tensor:
        """``(N,)`` each unit's share of the overlap the loss counts, in raster px^2 of alpha:
        a sample's alpha times ``relu(T - 1) / T`` at its pixel, ``T = C + O`` of its layer
        (as the forward has it). ``values``, ``index``, ``owner`` ``(M,)`` as from
        ``render_samples``; ``layer (N,)`` each unit's layer (long)."""
        n_layers = self.penalty.shape[0]
        flat, own = self.coverage(values, index, owner, layer)
        total = own + self.obstacles(own) if n_layers > 1 and self.has_obstacles else own
        at = total.reshape(-1)[flat]
        over = values * torch.relu(at - 1.0) / at.clamp_min(1e-6)
        return torch.zeros(n_units, dtype=values.dtype, device=values.device).index_add_(0, owner, over)

    @property
    def stats(self) -> dict:
        """Shares of the last forward (reads the sums back): overlap and outside of the
        drawn alpha, fill of the container (NaN without a closed container); 0 before one."""
        if self.sums is None:   # no forward yet
            return shares([0.0, 0.0, 0.0, 0.0], self.inside_total)
        return shares(self.sums.sum(1).tolist(), self.inside_total)

    def buffer(self, like: torch.Tensor) -> torch.Tensor:
        """The zeroed ``(L * S,)`` coverage buffer (allocated once)."""
        if self._cover is None or self._cover.dtype != like.dtype or self._cover.device != like.device:
            self._cover = torch.zeros(self.penalty.numel(), dtype=like.dtype, device=like.device)
            self._tables = None
        return self._cover

    def tables(self) -> tuple:
        """Fixed per-pixel tables (made once, in the buffer's dtype and device):
        ``fields (L, 4, S)`` penalty, outside, inside, 1 (one pass sums all four against
        the coverage), the pixel gradient where the total is at most 1 (``base (L, S)``),
        and what an over-full pixel adds (a number) and an under-full one takes away
        (``fill (L, S)``, None without fill); everything divided by the norm."""
        if self._tables is None:
            like = self._cover
            penalty, outside, inside = (t.to(like) for t in (self.penalty, self.outside, self.inside))
            fields = torch.stack([penalty, outside, inside, torch.ones_like(penalty)], dim=1)
            base = self.w_contain * penalty / self.norm
            fill = self.w_fill * inside / self.norm if self.w_fill else None
            self._tables = (fields, base, self.w_overlap / self.norm, fill)
        return self._tables


def shares(sums, inside_total: float) -> dict:
    """``{"overlap", "outside", "fill"}`` from summed ``(overlap, outside, drawn, covered)``."""
    overlap, outside, drawn, covered = sums
    drawn = max(drawn, 1e-6)
    return {"overlap": overlap / drawn, "outside": outside / drawn,
            "fill": covered / inside_total if inside_total > 0 else float("nan")}


class CanvasLoss(torch.autograd.Function):
    """``loss = CanvasLoss.apply(values, index, layer, terms)`` -> scalar.

    ``values (M,)`` sample alphas, ``index (M,)`` flat raster index within a
    slab, ``layer (M,)`` the layer of each sample (long), or None when there
    is one layer.

    A layer's values are attributed by its share ``C / T`` of a pixel's
    occupancy, which makes the overlap value exactly ``sum_p relu(T_p - 1)``
    over the layer's pixels when it has no obstacles (with obstacles, the
    layer's share of it). The backward is the pixel gradient of the module
    docstring's terms, gathered at the samples.
    """

    @staticmethod
    def forward(ctx, values, index, layer, terms: CanvasTerms):
        n_layers, size = terms.penalty.shape
        flat = index if layer is None or n_layers == 1 else layer * size + index
        cover = terms.buffer(values)
        cover.index_add_(0, flat, values)
        own = cover.view(n_layers, size)
        fields, base, over, fill = terms.tables()
        # contain, outside, inside . C and drawn alpha per layer: one pass over the slabs
        per = torch.bmm(fields, own[:, :, None])[..., 0]                       # (L, 4)
        if n_layers > 1 and terms.has_obstacles:
            total = own + terms.obstacles(own)                                  # T = C + O
            spill = torch.relu(total - 1.0)
            share = own / total.clamp_min(1e-6)
            excess = share * spill                                              # the layer's share
            overlap = excess.sum(1)
            # the container covered: none without a closed layer to fill (inside is all 0)
            covered = (share * fields[:, 2] * total.clamp(max=1.0)).sum(1) if terms.inside_total > 0 \
                else torch.zeros(n_layers, dtype=own.dtype, device=own.device)
        else:
            total = own
            spill = excess = (own - 1.0).clamp_min_(0.0)
            # overlap and inside . excess: the container covered is inside . min(C, 1)
            spilled = torch.bmm(fields[:, 2:], excess[:, :, None])[..., 0]      # (L, 2)
            overlap, covered = spilled[:, 1], per[:, 2] - spilled[:, 0]
        terms.sums = torch.stack([overlap, per[:, 1], per[:, 3], covered]).detach()
        gap = terms.inside_total - covered.sum()
        loss = (terms.w_overlap * overlap.sum() + terms.w_contain * per[:, 0].sum()
                + terms.w_fill * gap) / terms.norm
        # the pixel gradient, already divided by the norm, gathered at the samples; sign()
        # of the spill (1 over full, 0 else) instead of where(): a third of the time on a CPU
        pixel_grad = torch.add(base, torch.sign(spill), alpha=over)
        if fill is not None:
            pixel_grad.addcmul_(fill, torch.sign((1.0 - total).clamp_min_(0.0)), value=-1.0)
        ctx.save_for_backward(pixel_grad.reshape(-1).index_select(0, flat))
        cover.zero_()                                                           # leave the buffer zeroed
        return loss

    @staticmethod
    def backward(ctx, grad_out):
        (sample_grad,) = ctx.saved_tensors
        return grad_out * sample_grad, None, None, None
