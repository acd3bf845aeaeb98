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
The samples are scattered into the slabs once, and the obstacles are dense
passes over the ``(L, S)`` slabs; every term is then read at the samples
alone (a term is zero where a layer has no ink): each sample gathers its
pixel's total ``T`` and fixed tables, and holds the share ``alpha / T`` of its
pixel's terms, so the sums over samples are the sums over pixels, and the
pixel gradient is the sample's gradient, with no autograd through the canvas.
Where most samples are empty (``PACK_EMPTY``), only the inked ones are gathered and summed.
Nothing is read back to the host: the per-layer sums stay on the device
(``terms.sums``) for the solver to fetch.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import torch

from .strata import SCAN_BLOCK, RadialShadow, shadow, swept_along

#: the share of empty samples (alpha 0) over which the loss, on a CPU, gathers and sums the
#: inked samples alone: packing them costs a pass and three gathers, so a denser set sums
#: them all
PACK_EMPTY = 0.5


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
    #: ``(like, O (L, S) or None, inks)``: for coverage of ``like`` (shape, dtype, device),
    #: the obstacle buffer where no layer sees another's ink itself (rows of layers that rest
    #: on none stay 0; None otherwise),
    #: and per column-swept group its ink buffer ``(R, H + pad, W)``, padded with zero rows to
    #: whole scan blocks (``strata.SCAN_BLOCK``) once; see ``obstacles``
    _obstacle: tuple | None = None
    _tables: tuple | None = None               # fixed per-pixel tables, see ``tables``
    _rows: torch.Tensor | None = None          # (5, M) per-sample terms, see ``rows``
    _packed: torch.Tensor | None = None        # (5, >= K) per-inked-sample terms, see ``packed_rows``
    _onehot: tuple | None = None               # (layer, its one-hot), see ``per_layer``
    _rim: torch.Tensor | None = None           # samples whose rows 1 and 4 may not be 0 (None: any), see ``border_rows``

    @functools.cached_property
    def inside_total(self) -> float:
        """The fill target's area in raster px^2 (closed layers)."""
        return float(self.inside.sum())

    @functools.cached_property
    def inside_host(self):
        """The fill target ``(L, S)`` as a host numpy array (copied from the device once)."""
        return self.inside.cpu().numpy()

    @functools.cached_property
    def any_inside(self) -> bool:
        """Whether some layer has a fill target (a closed container; read once: it is fixed)."""
        return bool(self.inside.any())

    @functools.cached_property
    def any_blocks(self) -> bool:
        """Whether some layer sees another's ink itself (read once: the blocks are fixed)."""
        return bool(self.blocks.any())

    @functools.cached_property
    def has_obstacles(self) -> bool:
        """Whether some layer blocks on another (read once: the blocks are fixed)."""
        return self.any_blocks or (self.rests is not None and bool(self.rests.any()))

    @functools.cached_property
    def sweep_groups(self) -> tuple:
        """``((sweep, layers, rows), ...)``: the layers that rest on others, grouped by their
        sweep (layers swept alike are swept in one scan), as a device tensor and as ints; read
        once: the rests are fixed."""
        groups = {}
        for a, sweep in enumerate(self.sweeps):
            if sweep is not None and self.rests is not None and bool(self.rests[a].any()):
                groups.setdefault(sweep, (sweep, []))[1].append(a)
        device = self.penalty.device
        return tuple((sweep, torch.tensor(rows, device=device), tuple(rows)) for sweep, rows in groups.values())

    def obstacles(self, own: torch.Tensor, flat: torch.Tensor | None = None) -> torch.Tensor:
        """``O (L, S)`` from the coverage ``own (L, S)``: the ink of the layers each blocks
        on, and the shadow of those it rests on (see the module docstring). Where no layer
        sees another's ink itself (a stack), ``O`` is a buffer kept between calls, valid
        until the next call: each resting layer's row is overwritten, the others stay 0.
        With ``flat (M,)`` (samples' indices into the stacked slabs): ``O`` at those alone,
        ``(M,)``; the radial shadows are then resampled at the samples' pixels only."""
        like = (own.shape, own.dtype, own.device)
        if self._obstacle is None or self._obstacle[0] != like:
            # the zero slab is kept only where it is the obstacle (no blocks product)
            self._obstacle = (like, None if self.any_blocks else torch.zeros_like(own), {})
        # blocks is all zeros where every layer rests (a stack): skip its product
        obstacle = self.blocks.to(own) @ own if self.any_blocks else self._obstacle[1]
        inks, radial = self._obstacle[2], []
        for g, (sweep, layers, rows) in enumerate(self.sweep_groups):   # the resting layers
            h, w = self.shape
            rests = self.rests.index_select(0, layers).to(own)
            if flat is not None and isinstance(sweep, RadialShadow):   # read at the samples below
                radial.append((sweep, (rests @ own).clamp_(max=1.0), rows))
                continue
            if sweep == (0, False) and h % SCAN_BLOCK:
                # down the columns: the ink is written into zero rows padded to whole scan
                # blocks, so the scan pads nothing; the swept rows are its first h
                if g not in inks:
                    inks[g] = own.new_zeros(len(rows), h + (-h % SCAN_BLOCK), w)
                ink = inks[g].view(len(rows), -1)[:, :h * w]
                torch.matmul(rests, own, out=ink).clamp_(max=1.0)
                swept = shadow(inks[g], *sweep)[:, :h]
            else:
                ink = (rests @ own).clamp_(max=1.0)
                swept = swept_along(sweep, ink.view(len(rows), h, w))
            for k, a in enumerate(rows):   # a row at a time: index_add_ over rows is slow on a CPU
                if self.any_blocks:
                    obstacle[a] += swept[k].reshape(-1)
                else:
                    obstacle[a].copy_(swept[k].reshape(-1))
        if flat is None:
            return obstacle
        at = obstacle.reshape(-1).index_select(0, flat)
        for sweep, ink, rows in radial:   # without blocks the buffer's rows are stale: replaced
            sweep.onto(at, ink, rows, flat, add=self.any_blocks)
        return at

    def obstacle(self, own: torch.Tensor, a: int) -> torch.Tensor:
        """``(S,)`` row ``a`` of ``obstacles(own)``, computed alone (one sweep, not ``L``)."""
        obstacle = self.blocks[a].to(own) @ own if self.any_blocks else torch.zeros_like(own[a])
        sweep = self.sweeps[a] if self.sweeps else None
        if self.rests is not None and sweep is not None and bool(self.rests[a].any()):
            ink = (self.rests[a].to(own) @ own).clamp_(max=1.0).view(self.shape)
            obstacle = obstacle + swept_along(sweep, ink).reshape(-1)
        return obstacle

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

    def totals(self, cover: torch.Tensor, flat: torch.Tensor) -> torch.Tensor:
        """``(M,)`` the total ``T = C + O`` at each sample's pixel, from the flat coverage
        ``cover (L * S,)`` and the samples' indices into it ``flat (M,)``."""
        total = cover.index_select(0, flat)
        n_layers, size = self.penalty.shape
        if n_layers > 1 and self.has_obstacles and cover.device.type == "cpu":
            total += self.obstacles(cover.view(n_layers, size), flat)
        elif n_layers > 1 and self.has_obstacles:   # a GPU: whole slabs, no count read back
            total += self.obstacles(cover.view(n_layers, size)).reshape(-1).index_select(0, flat)
        return total

    def unit_overlap(self, values: torch.Tensor, index: torch.Tensor, owner: torch.Tensor,
                     layer: torch.Tensor, n_units: int) -> torch.Tensor:
        """``(N,)`` each unit's share of the overlap the loss counts, in raster px^2 of alpha:
        a sample's alpha times ``relu(T - 1) / T`` at its pixel, ``T = C + O`` of its layer
        (as the forward has it). ``values``, ``index``, ``owner`` ``(M,)`` as from
        ``render_samples``; ``layer (N,)`` each unit's layer (long)."""
        flat, own = self.coverage(values, index, owner, layer)
        at = self.totals(own.reshape(-1), flat)
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
        """``(penalty, outside, inside)``, each ``(L * S,)``: the fixed per-pixel tables of the
        stacked slabs, the containment penalty, the outside share and the fill target, made
        once, contiguous, in the buffer's dtype and device (three flat gathers are several
        times faster on a CPU than one of ``(L * S, 3)`` rows)."""
        if self._tables is None:
            self._tables = tuple(t.to(self._cover).reshape(-1).contiguous()
                                 for t in (self.penalty, self.outside, self.inside))
        return self._tables

    @functools.cached_property
    def border_table(self) -> torch.Tensor:
        """``(L, H + 1, W + 1)`` int32: the summed-area table of each layer's pixels where
        the containment penalty or the outside share is not 0 (made once: both are fixed)."""
        h, w = self.shape
        rim = ((self.penalty != 0) | (self.outside != 0)).view(-1, h, w).to(torch.int32)
        table = torch.zeros(rim.shape[0], h + 1, w + 1, dtype=torch.int32, device=rim.device)
        table[:, 1:, 1:] = rim.cumsum(1, dtype=torch.int32).cumsum(2, dtype=torch.int32)
        return table

    def border(self, index: torch.Tensor, plan, layer: torch.Tensor) -> torch.Tensor | None:
        """``(k,)`` long, ascending: the samples of the marks whose patch meets a pixel where
        its layer's containment penalty or outside share is not 0 (every other sample reads
        0 in both). ``index (M,)`` as ``render_samples`` drew it with ``plan`` (a
        ``raster.RenderPlan``, see its ``patches``); ``layer (N,)`` each unit's layer (long).
        None where that is over half the samples (reading them all costs less then)."""
        first, ph, pw, unit, whole = plan.patches
        (h, w), table = self.shape, self.border_table
        origin = index.index_select(0, first).long()
        r0, c0, a = origin // w, origin % w, layer.index_select(0, unit)
        r1, c1 = (r0 + ph).clamp_(max=h), (c0 + pw).clamp_(max=w)   # bounds only for ``whole``
        meets = (table[a, r1, c1] - table[a, r0, c1] - table[a, r1, c0] + table[a, r0, c0] > 0) | whole
        marks = torch.nonzero(meets).reshape(-1)
        count = (ph * pw).index_select(0, marks)
        total = int(count.sum())
        if 2 * total > len(index):
            return None
        # each mark's samples run from its first: sample k of the run is k - (the run's
        # start in the result) + first
        start = torch.cumsum(count, 0) - count
        return torch.arange(total, device=index.device) + torch.repeat_interleave(
            first.index_select(0, marks) - start, count, output_size=total)

    def border_rows(self, rows: torch.Tensor, values: torch.Tensor, flat: torch.Tensor,
                    border: torch.Tensor, packed: bool = False) -> torch.Tensor:
        """Write the outside and containment rows (1 and 4) of ``rows`` (``rows``, or
        ``packed_rows``, whose columns hold other samples each call: cleared whole): values
        times the outside share and the penalty at ``border`` (see ``border``), 0 at every
        other sample (where both tables are 0), clearing only the samples the last call
        wrote. Returns the penalty at ``border`` ``(k,)``; ``values``, ``flat`` ``(M,)``."""
        if packed or self._rim is None:
            rows[1].zero_()
            rows[4].zero_()
        else:
            rows[1].index_fill_(0, self._rim, 0.0)
            rows[4].index_fill_(0, self._rim, 0.0)
        tables, at = self.tables(), flat.index_select(0, border)
        v, penalty = values.index_select(0, border), tables[0].index_select(0, at)
        rows[1].index_copy_(0, border, v * tables[1].index_select(0, at))
        rows[4].index_copy_(0, border, v * penalty)
        if not packed:
            self._rim = border
        return penalty

    def rows(self, like: torch.Tensor) -> torch.Tensor:
        """The ``(5, M)`` buffer of the per-sample terms for samples ``like (M,)``, kept
        between calls while ``M`` holds: written in place, no fresh 5 M floats each call."""
        shape = (5, like.shape[0])
        if self._rows is None or self._rows.shape != shape or self._rows.dtype != like.dtype \
                or self._rows.device != like.device:
            # zeros: the covered row stays 0 where no layer has a fill target (never written)
            self._rows = torch.zeros(shape, dtype=like.dtype, device=like.device)
            self._rim = torch.zeros(0, dtype=torch.long, device=like.device)
        return self._rows

    def packed_rows(self, like: torch.Tensor) -> torch.Tensor:
        """``rows`` for the inked samples ``like (K,)`` alone: the first ``K`` columns of a
        kept buffer that grows as ``K`` does (``K`` changes every call)."""
        k = like.shape[0]
        if self._packed is None or self._packed.shape[1] < k or self._packed.dtype != like.dtype \
                or self._packed.device != like.device:
            self._packed = torch.zeros((5, k + k // 4), dtype=like.dtype, device=like.device)
        return self._packed[:, :k]

    def per_layer(self, rows: torch.Tensor, layer: torch.Tensor | None) -> torch.Tensor:
        """``(K, L)`` the per-sample ``rows (K, M)`` summed over each layer's samples
        (``layer (M,)`` long, or None with one layer), as a product with the samples' layer
        one-hot ``(M, L)``: made once per ``layer`` tensor (the solver keeps one per plan)."""
        n_layers = self.penalty.shape[0]
        if layer is None or n_layers == 1:
            return rows.sum(1, keepdim=True)
        if self._onehot is None or self._onehot[0] is not layer or self._onehot[1].dtype != rows.dtype:
            hot = torch.zeros(len(layer), n_layers, dtype=rows.dtype, device=rows.device)
            self._onehot = (layer, hot.scatter_(1, layer[:, None], 1.0))
        return rows @ self._onehot[1]


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
    def forward(ctx, values, index, layer, terms: CanvasTerms, border=None):
        n_layers, size = terms.penalty.shape
        flat = index if layer is None or n_layers == 1 else layer * size + index
        ctx.samples, inked = values.shape[0], None
        if values.device.type == "cpu" \
                and int(torch.count_nonzero(values)) < (1.0 - PACK_EMPTY) * values.shape[0]:
            # most samples are empty (a patch's corners; a thin mark's turning square): an
            # empty sample adds 0 to every sum, so only the inked ones are summed (on a CPU:
            # a GPU's queue would wait for the count)
            inked = torch.nonzero(values).reshape(-1)
            values, flat = values.index_select(0, inked), flat.index_select(0, inked)
            layer = None if layer is None else layer.index_select(0, inked)
            if border is not None:   # the border's samples among the inked: their places there
                at = torch.searchsorted(inked, border).clamp_(max=max(len(inked) - 1, 0))
                border = at[inked.index_select(0, at) == border] if len(inked) else at[:0]
        cover = terms.buffer(values)
        cover.index_add_(0, flat, values)
        total = terms.totals(cover, flat)                                       # T = C + O
        cover.zero_()                                                           # leave the buffer zeroed
        tables = terms.tables()
        # the fill target is gathered only where some layer has one (open layouts: all 0)
        inside = tables[2].index_select(0, flat) if terms.any_inside else None
        spill = torch.relu(total - 1.0)
        share = values / total.clamp_min(1e-6)   # the sample's share of its pixel, per unit of T
        # per layer: overlap (its share of the spill), outside, drawn alpha, the container
        # covered (its share of inside . min(T, 1)), and the containment cost; each row
        # written into the kept buffer
        rows = terms.rows(values) if inked is None else terms.packed_rows(values)
        torch.mul(share, spill, out=rows[0])
        if border is None:
            penalty, outside = tables[0].index_select(0, flat), tables[1].index_select(0, flat)
            torch.mul(values, outside, out=rows[1])
            torch.mul(values, penalty, out=rows[4])
            terms._rim = None
        else:   # both tables are read, and both rows written, at the border's samples alone
            penalty = terms.border_rows(rows, values, flat, border, packed=inked is not None)
        rows[2].copy_(values)
        if inside is not None:   # without a fill target the covered row stays 0 (``rows``)
            torch.mul(share, inside, out=rows[3]).mul_(total.clamp(max=1.0))
        sums = terms.per_layer(rows, layer)                                    # (5, L)
        terms.sums = sums[:4].detach()
        gap = terms.inside_total - sums[3].sum()
        loss = (terms.w_overlap * sums[0].sum() + terms.w_contain * sums[4].sum()
                + terms.w_fill * gap) / terms.norm
        # each sample's pixel gradient, divided by the norm; sign() of the spill (1 over full,
        # 0 else) instead of where(): a third of the time on a CPU
        grad = torch.sign(spill).mul_(terms.w_overlap / terms.norm)
        if border is None:
            grad.add_(penalty, alpha=terms.w_contain / terms.norm)
        else:   # 0 penalty elsewhere adds nothing
            grad.index_add_(0, border, penalty, alpha=terms.w_contain / terms.norm)
        if terms.w_fill and inside is not None:   # with no fill target the term adds 0
            grad.addcmul_(inside, torch.sign((1.0 - total).clamp_min_(0.0)), value=-terms.w_fill / terms.norm)
        ctx.save_for_backward(grad, inked)
        return loss

    @staticmethod
    def backward(ctx, grad_out):
        sample_grad, inked = ctx.saved_tensors
        if inked is not None:   # an empty sample's alpha has no gradient (but on an inked texel's edge)
            sample_grad = sample_grad.new_zeros(ctx.samples).index_copy_(0, inked, sample_grad)
        return grad_out * sample_grad, None, None, None, None
