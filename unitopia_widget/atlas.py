"""Sprite atlas: the sprite pyramids of several marks packed level by level.

A layer that draws a group of marks has one sprite pyramid per distinct mark.
Rendering each (sprite, level, patch) group with its own ``grid_sample`` call
makes the cost grow with the number of marks; the atlas stacks level ``l`` of
every sprite into one texture ``(1, 1, H_l, W_l)``, tiles top to bottom with
``GAP`` zero texels around each, so marks with different sprites that share a
level and patch shape render in one call. Sampling a tile is exactly sampling
its sprite with zero padding: coordinates more than one texel outside the
tile (where bilinear weights could reach a neighbour) are masked to zero.
"""
from __future__ import annotations

import torch

GAP = 2   # zero texels between tiles and around the atlas


class SpriteAtlas:
    """Indexable like the list of pyramids it packs (``atlas[s][level]``)."""

    def __init__(self, pyramids: list):
        self.pyramids = list(pyramids)
        like = self.pyramids[0][0]
        self.levels = []   # per level: (texture, top (S,), height (S,), width (S,)) in texels
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
            as_t = lambda v: torch.tensor(v, dtype=like.dtype, device=like.device)  # noqa: E731
            self.levels.append((texture, as_t(tops), as_t([t.shape[-2] for t in tiles]),
                                as_t([t.shape[-1] for t in tiles])))

    def __len__(self) -> int:
        return len(self.pyramids)

    def __getitem__(self, sprite: int) -> list:
        return self.pyramids[sprite]

    def merge(self, groups: list) -> list:
        """Groups ``(indices, sprite, level, ph, pw)`` merged across sprites:
        ``(indices, sprites (n,) long tensor, level, ph, pw)``."""
        merged = {}
        for idx, sprite, level, ph, pw in groups:
            merged.setdefault((level, ph, pw), []).append((idx, sprite))
        out = []
        for (level, ph, pw), parts in merged.items():
            idx = torch.cat([torch.as_tensor(i) for i, _ in parts])
            sprites = torch.cat([torch.full((len(i),), s, dtype=torch.long) for i, s in parts])
            out.append((idx.numpy(), sprites, level, ph, pw))
        return out

    def grid(self, level: int, sprites: torch.Tensor, gx: torch.Tensor, gy: torch.Tensor):
        """``(texture, grid (n, ph, pw, 2), keep (n, ph, pw))``: sprite coordinates
        ``gx, gy`` in [-1, 1] of marks drawing ``sprites`` mapped into the level's texture."""
        texture, top, height, width = self.levels[level]
        s = sprites.to(texture.device)
        h, w, y0 = height[s][:, None, None], width[s][:, None, None], top[s][:, None, None]
        x = GAP + (gx + 1) * (w / 2)                   # texels from the texture's left edge
        y = y0 + (gy + 1) * (h / 2)
        keep = (x > GAP - 1) & (x < GAP + w + 1) & (y > y0 - 1) & (y < y0 + h + 1)
        th, tw = texture.shape[-2:]
        return texture, torch.stack([2 * x / tw - 1, 2 * y / th - 1], dim=-1), keep
