"""Image-space losses on the coverage raster, with a hand-written backward.

Every layer has its own coverage slab ``C[a]`` (the sum of its marks' footprint
alphas per raster pixel). A layer ``a`` that blocks on layers ``b`` sees their
coverage as obstacles ``O[a] = sum_b C[b]`` with gradients stopped: one-way
blocking (paper section 4.1.2). With ``T = C + O``, per raster pixel:

* overlap     ``relu(T - 1)``                 (paper eq. 3 with tau = 1 on coverage)
* containment ``alpha * field``               (a signed-distance penalty, eq. 4 improved)
* fill        ``inside * relu(1 - T)``        (closed boundaries only)

All terms are divided by ``terms.norm`` (the marks' footprint area, held
constant during a phase) so the loss reads as a fraction of the marks' area. The backward only gathers a per-pixel gradient
image at the sample indices, which is far cheaper than autograd through the
``(L, H, W)`` canvas.
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


class CanvasLoss(torch.autograd.Function):
    """``loss = CanvasLoss.apply(values, index, layer, terms)`` -> scalar.

    ``values (M,)`` sample alphas, ``index (M,)`` flat raster index within a
    slab, ``layer (M,)`` the layer of each sample (long).
    """

    @staticmethod
    def forward(ctx, values, index, layer, terms: CanvasTerms):
        n_layers, size = terms.penalty.shape
        flat = layer * size + index
        cover = torch.zeros(n_layers * size, dtype=values.dtype, device=values.device)
        cover.index_add_(0, flat, values)
        cover = cover.view(n_layers, size)
        total = cover + terms.blocks @ cover if n_layers > 1 else cover
        area = terms.norm
        excess = torch.relu(total - 1.0)
        gap = terms.inside * torch.relu(1.0 - total)
        outside = (values * terms.outside.view(-1)[flat]).sum()
        contain = (values * terms.penalty.view(-1)[flat]).sum()
        overlap = excess.sum()
        fill_gap = gap.sum()
        loss = (terms.w_overlap * overlap + terms.w_contain * contain + terms.w_fill * fill_gap) / area
        pixel_grad = terms.w_overlap * (total > 1.0).to(values.dtype)
        if terms.w_fill:
            pixel_grad -= terms.w_fill * terms.inside * (total < 1.0).to(values.dtype)
        sample_grad = pixel_grad.view(-1)[flat] + terms.w_contain * terms.penalty.view(-1)[flat]
        ctx.save_for_backward(sample_grad / area)
        inside_total = terms.inside.sum()
        terms.stats = {
            "overlap": float(overlap / values.sum().clamp_min(1e-6)),
            "outside": float(outside / values.sum().clamp_min(1e-6)),
            "fill": float(1.0 - fill_gap / inside_total) if float(inside_total) > 0 else float("nan"),
        }
        return loss

    @staticmethod
    def backward(ctx, grad_out):
        (sample_grad,) = ctx.saved_tensors
        return grad_out * sample_grad, None, None, None
