"""Image-space losses on the coverage raster, with a hand-written backward.

Every layer has its own coverage slab ``C[a]`` (the sum of its marks' footprint
alphas per raster pixel). A layer ``a`` that blocks on layers ``b`` sees their
coverage as obstacles ``O[a] = sum_b C[b]`` with gradients stopped: one-way
blocking (paper section 4.1.2). Layers that share a container and do not
block each other see each other both ways, so they collide as one layer. With ``T = C + O``, per raster pixel:

* overlap     ``relu(T - 1)``                 (paper eq. 3 with tau = 1 on coverage)
* containment ``alpha * field``               (a signed-distance penalty, eq. 4 improved)
* fill        ``inside * relu(1 - T)``        (closed boundaries only; the gap left open)

All terms are divided by ``terms.norm`` (the marks' footprint area, held
constant during a phase) so the loss reads as a fraction of the marks' area.
The backward only gathers the per-pixel gradient at the sample indices,
which is far cheaper than autograd through the ``(L, H, W)`` canvas.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import torch


@dataclass
class CanvasTerms:
    """Fixed inputs of the canvas loss. Shapes: ``L`` layers, ``S`` raster pixels."""

    penalty: torch.Tensor      # (L, S) containment cost per unit alpha, 0 inside
    outside: torch.Tensor      # (L, S) share of each pixel outside the allowed region
    inside: torch.Tensor       # (L, S) fill target: container coverage on closed layers, 0 on open ones
    blocks: torch.Tensor       # (L, L) float, blocks[a, b] = 1 when layer a treats b as obstacle
    norm: float = 1.0          # the marks' total footprint area in raster px^2, a constant normaliser
    w_overlap: float = 1.0
    w_contain: float = 1.0
    w_fill: float = 0.0
    stats: dict = field(default_factory=dict)  # filled by each forward: overlap, outside, fill
    #: filled by each forward: per-layer sums ``(3, L)`` (overlap, outside, drawn alpha), numpy
    layer_sums: object = None
    _cover: torch.Tensor | None = None         # (L * S,) coverage buffer, all zeros between calls

    @property
    def inside_total(self) -> float:
        """The fill target's area in raster px^2 (closed layers)."""
        if not hasattr(self, "_inside_total"):
            self._inside_total = float(self.inside.sum())
        return self._inside_total

    def buffer(self, like: torch.Tensor) -> torch.Tensor:
        """The zeroed ``(L * S,)`` coverage buffer (allocated once)."""
        if self._cover is None or self._cover.dtype != like.dtype or self._cover.device != like.device:
            self._cover = torch.zeros(self.penalty.numel(), dtype=like.dtype, device=like.device)
        return self._cover


class CanvasLoss(torch.autograd.Function):
    """``loss = CanvasLoss.apply(values, index, layer, terms)`` -> scalar.

    ``values (M,)`` sample alphas, ``index (M,)`` flat raster index within a
    slab, ``layer (M,)`` the layer of each sample (long).

    Only the pixels the samples touch are visited: the cost is O(M), not
    O(L x H x W). Values are attributed to samples by their share ``C / T`` of a
    pixel's occupancy, which makes the overlap value exactly
    ``sum_p relu(T_p - 1)`` over the layer's pixels when it has no obstacles
    (with obstacles, the layer's share of it). The backward is the pixel
    gradient of the module docstring's terms, gathered at the samples.
    """

    @staticmethod
    def forward(ctx, values, index, layer, terms: CanvasTerms):
        n_layers, size = terms.penalty.shape
        flat = layer * size + index
        cover = terms.buffer(values)
        cover.index_add_(0, flat, values)
        own = cover[flat]                                          # (M,) C at each sample's pixel
        total = own
        if n_layers > 1 and bool(terms.blocks.any()):
            stacked = cover.view(n_layers, size)[:, index]          # (L, M) every slab at the pixel
            total = own + (terms.blocks[layer] * stacked.T).sum(1)  # + obstacles O
        cover.index_fill_(0, flat, 0.0)                            # leave the buffer zeroed
        share = values / total.clamp_min(1e-6)
        outside_at = terms.outside.view(-1)[flat]
        penalty_at = terms.penalty.view(-1)[flat]
        inside_at = terms.inside.view(-1)[flat]
        overlap = (share * torch.relu(total - 1.0)).sum()
        covered = (share * inside_at * torch.clamp(total, max=1.0)).sum()
        contain = (values * penalty_at).sum()
        gap = terms.inside_total - covered
        area = terms.norm
        loss = (terms.w_overlap * overlap + terms.w_contain * contain + terms.w_fill * gap) / area
        sample_grad = (terms.w_overlap * (total > 1.0).to(values.dtype) + terms.w_contain * penalty_at)
        if terms.w_fill:
            sample_grad -= terms.w_fill * inside_at * (total < 1.0).to(values.dtype)
        ctx.save_for_backward(sample_grad / area)
        drawn = values.sum().clamp_min(1e-6)
        outside = (values * outside_at).sum()
        if n_layers == 1:
            sums = torch.stack([overlap, outside, values.sum()])[:, None]
        else:
            sums = torch.zeros((3, n_layers), dtype=values.dtype, device=values.device)
            for row, v in enumerate((share * torch.relu(total - 1.0), values * outside_at, values)):
                sums[row].index_add_(0, layer, v)
        terms.layer_sums = sums.detach().cpu().numpy()
        terms.stats = {
            "overlap": float(overlap / drawn),
            "outside": float(outside / drawn),
            "fill": float(covered / terms.inside_total) if terms.inside_total > 0 else float("nan"),
        }
        return loss

    @staticmethod
    def backward(ctx, grad_out):
        (sample_grad,) = ctx.saved_tensors
        return grad_out * sample_grad, None, None, None
