#!/usr/bin/env python3
"""PyTorch parity of the tpf TCN (optional test; exit 77 = SKIPPED where torch is missing).

1. A PyTorch TpfTcn with random weights is exported (export_tpf_weights) and streamed by the core
   engine (tcn_stream): every output equals PyTorch's to 1e-9 (both in double).
2. A tpf weight file (trained by `tpf train`) loads into PyTorch (load_tpf_weights) and gives the
   core engine's outputs to 1e-9.
3. Side by side: the core engine's median step time and PyTorch's (one step = one forward over
   the receptive field, batch 1, double, no_grad), and their ratio (informative, not asserted).
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time

SKIP = 77


def stream(tool, weights, inputs, folder):
    """Runs the core engine over `inputs` (T x In); returns (low, high) as T x Out tensors and
    the median step time [us]."""
    import torch
    inputs_csv = os.path.join(folder, "inputs.csv")
    outputs_csv = os.path.join(folder, "outputs.csv")
    with open(inputs_csv, "w", encoding="utf-8") as f:
        for row in inputs.tolist():
            f.write(",".join(repr(v) for v in row) + "\n")
    done = subprocess.run([tool, weights, inputs_csv, outputs_csv], check=True,
                          capture_output=True, text=True)
    with open(outputs_csv, encoding="utf-8") as f:
        rows = [[float(v) for v in line.split(",")] for line in f if line.strip()]
    out = torch.tensor(rows, dtype=torch.float64)
    half = out.shape[1] // 2
    return out[:, :half], out[:, half:], float(done.stdout.strip())


def compare(model, tool, weights, inputs, folder, label):
    import torch
    with torch.no_grad():
        low, high = model(inputs.T.unsqueeze(0))
    c_low, c_high, micros = stream(tool, weights, inputs, folder)
    error = max((low[0].T - c_low).abs().max().item(), (high[0].T - c_high).abs().max().item())
    scale = max(low.abs().max().item(), high.abs().max().item(), 1.0)
    print(f"{label}: {inputs.shape[0]} steps, max |PyTorch - tpf| = {error:.3g} "
          f"(outputs up to {scale:.3g})")
    return error <= 1e-9 * scale, micros


def torch_step_micros(model, inputs_per_step):
    """Median time of one PyTorch step: a forward over the last R samples (batch 1)."""
    import torch
    r = model.receptive_field
    window = torch.randn(1, model.inputs, r, dtype=torch.float64)
    times = []
    with torch.no_grad():
        for _ in range(inputs_per_step):
            start = time.perf_counter()
            model(window)
            times.append((time.perf_counter() - start) * 1e6)
    times.sort()
    return times[len(times) // 2]


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--stream", required=True, help="the tcn_stream tool")
    parser.add_argument("--module-dir", required=True, help="folder of tpf_tcn.py")
    parser.add_argument("--weights", help="a trained tpf weight file to load into PyTorch")
    args = parser.parse_args()
    try:
        import torch
    except ImportError:
        print("SKIPPED: PyTorch is not installed (Debian: apt-get install python3-torch); the "
              "parity of src/offline/compensator_training/torch/tpf_tcn.py with the core engine was not checked")
        return SKIP
    sys.path.insert(0, args.module_dir)
    from tpf_tcn import TpfTcn, export_tpf_weights, load_tpf_weights

    torch.manual_seed(5)
    torch.set_num_threads(1)
    ok = True
    with tempfile.TemporaryDirectory() as folder:
        for inputs, hidden, outputs in ((5, 16, 1), (5, 32, 1), (20, 32, 4)):
            model = TpfTcn(inputs, hidden, 4, 4, outputs).to(torch.float64)
            with torch.no_grad():
                model.mean.copy_(torch.randn(inputs))
                model.std.copy_(torch.rand(inputs) + 0.5)
                for p in model.parameters():  # biases too, so no unit is idle
                    p.uniform_(-0.4, 0.4)
            path = os.path.join(folder, f"torch_{inputs}_{hidden}_{outputs}.json")
            export_tpf_weights(model, path)
            x = torch.randn(600, inputs, dtype=torch.float64) * 2.0
            good, micros = compare(model, args.stream, path, x, folder,
                                   f"PyTorch -> tpf, {inputs} -> {hidden} -> {outputs}")
            ok &= good
            torch_micros = torch_step_micros(model, 300)
            print(f"  step time (median, double, 1 thread): tpf {micros:.2f} us, PyTorch "
                  f"{torch_micros:.1f} us, ratio {torch_micros / max(micros, 1e-3):.0f}x")
        if args.weights:
            model = load_tpf_weights(args.weights)
            x = torch.zeros(800, model.inputs, dtype=torch.float64)
            t = torch.arange(800, dtype=torch.float64) * 0.0025
            x[:, 0] = 0.5 * torch.sin(1.3 * t)                # q [rad]
            x[:, 1] = 0.65 * torch.cos(1.3 * t)               # q' [rad/s]
            x[:, 2] = -0.845 * torch.sin(1.3 * t)             # q'' [rad/s^2]
            x[:, 4] = 400.0 * torch.tanh(x[:, 1] / 0.01)      # nominal friction [mA]
            good, _ = compare(model, args.stream, args.weights, x, folder,
                              f"tpf -> PyTorch, {os.path.basename(args.weights)}")
            ok &= good
    print("PASSED" if ok else "FAILED: PyTorch and tpf outputs differ")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
