"""Sprite atlas: the sprite pyramids of several marks packed level by level.

A layer that draws a group of marks has one sprite pyramid per distinct mark.
Rendering each (sprite, level, patch) group with its own ``grid_sample`` call
makes the cost grow with the number of marks; the atlas stacks level ``l`` of
every sprite into one texture ``(1, 1, H_l, W_l)``, tiles top to bottom with
``GAP`` zero texels around each, so marks with different sprites that share a
level and patch shape render in one call. Sampling a tile is exactly sampling
its sprite with zero padding: coordinates are clamped to one texel around the
tile, where the bilinear weights only reach the zero gap (so the value there is
0 and so is the gradient) and never a neighbour.
"""
from __future__ import annotations

import numpy as np
import torch

GAP = 2   # zero texels between tiles and around the atlas


class SpriteAtlas:
    """Indexable like the list of pyramids it packs (``atlas[s][level]``)."""

    def __init__(self, pyramids: list):
        self.pyramids = list(pyramids)
        like = self.pyramids[0][0]
        self.levels = []   # per level: (texture, (S, 8) affine maps and bounds, see ``grid``)
        for level in range(min(len(p) for p in self.pyramids)):
            tiles = [p[level] for p in self.pyramids]
            width = max(t.shape[-1] for t in tiles) + 2 * GAP
            tops, y = [], GAP
            for t in tiles:
                tops.append(y)
                y += t.shape[-2] + GAP
            texture = torch.zeros((1, 1, y, width), dtype=like.dtype, device=like.device)
            for t, top in zip(tiles, tops):
                texture[..., top:top + t.shape[-2], GAP:GAP + t.shape[-1]] = t
            rows = []
            for t, top in zip(tiles, tops):
                h, w = t.shape[-2:]
                # sprite x in [-1, 1] -> texture x: GAP + (x + 1) w / 2 texels, normalised by the width
                rows.append([w / width, (2 * GAP + w) / width - 1, 2 * (GAP - 1) / width - 1,
                             2 * (GAP + w + 1) / width - 1,
                             h / y, (2 * top + h) / y - 1, 2 * (top - 1) / y - 1, 2 * (top + h + 1) / y - 1])
            self.levels.append((texture, torch.tensor(rows, dtype=like.dtype, device=like.device)))

    def __len__(self) -> int:
        return len(self.pyramids)

    def __getitem__(self, sprite: int) -> list:
        return self.pyramids[sprite]

    def merge(self, groups: list) -> list:
        """Groups ``(indices, sprite, level, ph, pw)`` merged across sprites:
        ``(indices, sprites (n,) long tensor, level, ph, pw)``. Marks of one level whose
        patches have the same long side share one patch of the largest height and width
        among them: marks of different aspects would otherwise split into many small calls."""
        merged = {}
        for idx, sprite, level, ph, pw in groups:
            merged.setdefault((level, max(ph, pw)), []).append((idx, sprite, ph, pw))
        out = []
        for (level, _), parts in merged.items():
            idx = np.concatenate([p[0] for p in parts])
            sprites = torch.cat([torch.full((len(p[0]),), p[1], dtype=torch.long) for p in parts])
            out.append((idx, sprites, level, max(p[2] for p in parts), max(p[3] for p in parts)))
        return out

    def grid(self, level: int, sprites: torch.Tensor, gx: torch.Tensor, gy: torch.Tensor):
        """``(texture, grid (n, ph, pw, 2))``: sprite coordinates ``gx, gy`` in [-1, 1]
        of marks drawing ``sprites`` mapped into the level's texture (normalised)."""
        texture, table = self.levels[level]
        m = table[sprites.to(texture.device)][:, None, None, :]          # (n, 1, 1, 8)
        x = torch.clamp(gx * m[..., 0] + m[..., 1], m[..., 2], m[..., 3])
        y = torch.clamp(gy * m[..., 4] + m[..., 5], m[..., 6], m[..., 7])
        return texture, torch.stack([x, y]).permute(1, 2, 3, 0)   # strided: see render_samples
