"""Adam for the placement parameters, without ``torch.optim``.

The first ``torch.optim.Adam`` of a process imports ``torch._dynamo`` (about
2 s on a 2-core CPU): more than a whole layout of 200 marks. This is the same
update (Kingma and Ba, with PyTorch's bias corrections and epsilon placement),
applied in place under ``no_grad``; ``param_groups`` and ``state`` read and
write like ``torch.optim``'s, so a caller can change a group's ``lr`` or reset
a unit's moments.
"""
from __future__ import annotations

import math

import torch


class Adam:
    """``Adam([{"params": [...], "lr": lr}, ...], betas=(b1, b2), eps=eps)``."""

    def __init__(self, param_groups: list[dict], betas=(0.9, 0.999), eps: float = 1e-8):
        self.param_groups = [dict(g, params=list(g["params"])) for g in param_groups]
        self.betas, self.eps = betas, eps
        self.state: dict = {}   # param -> {"step", "exp_avg", "exp_avg_sq"}

    def zero_grad(self, set_to_none: bool = True) -> None:
        for group in self.param_groups:
            for param in group["params"]:
                param.grad = None

    @torch.no_grad()
    def step(self) -> None:
        b1, b2 = self.betas
        for group in self.param_groups:
            for param in group["params"]:
                if param.grad is None:
                    continue
                state = self.state.get(param)
                if state is None:
                    state = self.state[param] = {"step": 0, "exp_avg": torch.zeros_like(param),
                                                 "exp_avg_sq": torch.zeros_like(param)}
                state["step"] += 1
                m, v, grad = state["exp_avg"], state["exp_avg_sq"], param.grad
                m.lerp_(grad, 1 - b1)
                v.mul_(b2).addcmul_(grad, grad, value=1 - b2)
                correction1 = 1 - b1 ** state["step"]
                correction2 = math.sqrt(1 - b2 ** state["step"])
                denom = (v.sqrt() / correction2).add_(self.eps)
                param.addcdiv_(m, denom, value=-group["lr"] / correction1)
