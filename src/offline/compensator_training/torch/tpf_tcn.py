"""The tpf friction-compensator TCN in PyTorch, and its weight-file export and import.

The network is the one of include/tpf/nn/tcn.hpp (docs/tcn.md): with h_{-1} = (x - mean) / std,
d_l = 2**l and K the kernel size, block l = 0 ... L-1 is

    h_l(t) = ReLU(b_l + sum_{k=0}^{K-1} W_{l,k} h_{l-1}(t - (K-1-k) d_l) + P_l h_{l-1}(t))

(P_0 a 1x1 projection when inputs != hidden, P_l = I otherwise), and two linear heads read the
last block: low(t) = A_low h(t) + c_low, high(t) = A_high h(t) + c_high, output = low + high.
The module's state_dict names are the weight file's tensor names (blocks.<l>.conv.weight,
blocks.<l>.conv.bias, blocks.0.downsample.weight, head_low.weight, ...), so a model trained in
PyTorch is exported by `export_tpf_weights` and loaded by tpf::load_tcn_weights unchanged.

Streaming in tpf starts with reset(x_0): the history holds x_0 for the whole receptive field.
`TpfTcn.forward` does the same: it repeats the first sample R - 1 times on the left and then
applies valid (unpadded) causal convolutions, so output t sees exactly what Tcn::step saw.
"""

import json

import torch
from torch import nn

FORMAT = "tpf-tcn-weights"
VERSION = 2  # torque inputs and outputs of a compensator in N·m


class TpfBlock(nn.Module):
    """One residual block: causal dilated convolution plus skip, then ReLU."""

    def __init__(self, inputs, hidden, kernel, dilation, project):
        super().__init__()
        self.dilation = dilation
        self.conv = nn.Conv1d(inputs, hidden, kernel, dilation=dilation)
        self.downsample = nn.Conv1d(inputs, hidden, 1, bias=False) if project else None

    def forward(self, h):
        """h: (batch, C_in, T) -> (batch, hidden, T - (K-1) d) (valid convolution)."""
        y = self.conv(h)
        skip = h[:, :, h.shape[2] - y.shape[2]:]
        y = y + (self.downsample(skip) if self.downsample is not None else skip)
        return torch.relu(y)


class TpfTcn(nn.Module):
    """TCN with `inputs` raw input channels, `hidden` channels, `levels` blocks, kernel `kernel`
    and `outputs` outputs; mean/std are the input normalisation (buffers, exported)."""

    def __init__(self, inputs, hidden, levels, kernel=4, outputs=1):
        super().__init__()
        self.inputs, self.hidden, self.levels = inputs, hidden, levels
        self.kernel, self.outputs = kernel, outputs
        self.blocks = nn.ModuleList(
            TpfBlock(inputs if l == 0 else hidden, hidden, kernel, 2**l,
                     project=(l == 0 and inputs != hidden)) for l in range(levels))
        self.head_low = nn.Linear(hidden, outputs)
        self.head_high = nn.Linear(hidden, outputs)
        self.register_buffer("mean", torch.zeros(inputs))
        self.register_buffer("std", torch.ones(inputs))

    @property
    def receptive_field(self):
        """R = 1 + (K - 1)(2^L - 1) samples."""
        return 1 + (self.kernel - 1) * (2**self.levels - 1)

    def forward(self, x):
        """x: raw inputs (batch, inputs, T) -> (low, high), each (batch, outputs, T): the outputs
        Tcn::step gives after reset(x[:, :, 0])."""
        h = (x - self.mean[None, :, None]) / self.std[None, :, None]
        first = h[:, :, :1].expand(-1, -1, self.receptive_field - 1)
        h = torch.cat([first, h], dim=2)
        for block in self.blocks:
            h = block(h)
        h = h.transpose(1, 2)  # (batch, T, hidden)
        return self.head_low(h).transpose(1, 2), self.head_high(h).transpose(1, 2)


def export_tpf_weights(model, path):
    """Writes `model` (a TpfTcn, weights and normalisation) as a tpf weight file (version 2)."""
    tensors = {}
    for name, value in model.state_dict().items():
        if name in ("mean", "std"):
            continue
        v = value.detach().to(torch.float64).cpu()
        tensors[name] = {"shape": list(v.shape), "values": v.reshape(-1).tolist()}
    document = {
        "format": FORMAT,
        "version": VERSION,
        "architecture": {
            "inputs": model.inputs, "hidden": model.hidden, "levels": model.levels,
            "kernel": model.kernel, "outputs": model.outputs, "activation": "relu",
            "dilations": [2**l for l in range(model.levels)],
            "receptive_field": model.receptive_field,
        },
        "normalisation": {"mean": model.mean.tolist(), "std": model.std.tolist()},
        "tensors": tensors,
    }
    with open(path, "w", encoding="utf-8") as f:
        json.dump(document, f)


def load_tpf_weights(path, dtype=torch.float64):
    """Reads a tpf weight file (e.g. written by `tpf train`) into a new TpfTcn."""
    with open(path, encoding="utf-8") as f:
        document = json.load(f)
    if document.get("format") != FORMAT or document.get("version") != VERSION:
        raise ValueError(f"{path}: not a {FORMAT} file of version {VERSION}")
    a = document["architecture"]
    model = TpfTcn(a["inputs"], a["hidden"], a["levels"], a["kernel"], a["outputs"]).to(dtype)
    state = {"mean": torch.tensor(document["normalisation"]["mean"], dtype=dtype),
             "std": torch.tensor(document["normalisation"]["std"], dtype=dtype)}
    for name, tensor in document["tensors"].items():
        state[name] = torch.tensor(tensor["values"], dtype=dtype).reshape(tensor["shape"])
    model.load_state_dict(state, strict=True)
    return model
