#!/usr/bin/env python3
"""Independent PyTorch reference of the colmap-gcn GCN (Yan et al., Sec. 3.3).

A plain torch re-implementation in the style of gcn_clustering: GraphConv
layers ReLU(cat([X, G X]) W + b) on dense adjacency matrices, then
Linear -> PReLU(channels) -> Linear(., 1); BCE-with-logits on the 1-hop nodes,
gradients by autograd. It shares no code with the C++ implementation.

Modes
  check DIR.. for each DIR: read DIR/meta.txt, DIR/*.bin written by the C++
              test, write DIR/out_logits_<g>.bin, DIR/out_grads.bin and
              DIR/out_loss.bin (float64). Exits 77 without torch/numpy.
  bench       time the forward pass per query (batch of one QES, as
              gcn_clustering's test loop) with a fixed thread count

Binary files are raw little-endian arrays (float32 inputs, float64 outputs).
Parameter order of the flat weight / gradient arrays (C++ GcnParameterLayout):
  for each GCN layer: W (2*in x out, row-major), b (out)
  FC1 weight (in x fc, row-major; i.e. torch weight transposed), FC1 bias (fc)
  PReLU slopes (fc), FC2 weight (fc), FC2 bias (1)
"""

import argparse
import os
import sys
import time

try:
    import numpy as np
    import torch
    import torch.nn as nn
    import torch.nn.functional as F
except ImportError as error:  # The C++ test skips on exit code 77.
    print("gcn_reference.py needs torch and numpy: %s" % error, file=sys.stderr)
    sys.exit(77)


class GraphConv(nn.Module):
    def __init__(self, in_dim, out_dim):
        super().__init__()
        self.weight = nn.Parameter(torch.empty(2 * in_dim, out_dim))
        self.bias = nn.Parameter(torch.zeros(out_dim))
        nn.init.xavier_uniform_(self.weight)

    def forward(self, x, g):
        agg = torch.matmul(g, x)
        cat = torch.cat([x, agg], dim=-1)
        return F.relu(torch.matmul(cat, self.weight) + self.bias)


class Gcn(nn.Module):
    def __init__(self, input_dim, gcn_dims, fc_dim):
        super().__init__()
        dims = [input_dim] + list(gcn_dims)
        self.convs = nn.ModuleList(
            [GraphConv(dims[i], dims[i + 1]) for i in range(len(gcn_dims))])
        self.fc1 = nn.Linear(gcn_dims[-1], fc_dim)
        self.prelu = nn.PReLU(fc_dim)
        self.fc2 = nn.Linear(fc_dim, 1)

    def forward(self, x, g, num_one_hop):
        for conv in self.convs:
            x = conv(x, g)
        x = x[..., :num_one_hop, :]
        lead = x.shape[:-1]
        x = x.reshape(-1, x.shape[-1])  # PReLU channels are the last dim
        return self.fc2(self.prelu(self.fc1(x))).reshape(lead)

    def flat_parameters(self):
        """(tensor, transpose?) in the C++ flat layout order."""
        out = []
        for conv in self.convs:
            out += [(conv.weight, False), (conv.bias, False)]
        out += [(self.fc1.weight, True), (self.fc1.bias, False),
                (self.prelu.weight, False), (self.fc2.weight, True),
                (self.fc2.bias, False)]
        return out

    def load_flat(self, flat):
        pos = 0
        with torch.no_grad():
            for tensor, transpose in self.flat_parameters():
                shape = tensor.t().shape if transpose else tensor.shape
                count = int(np.prod(shape))
                values = torch.from_numpy(
                    flat[pos:pos + count].reshape(shape)).to(tensor.dtype)
                tensor.copy_(values.t() if transpose else values)
                pos += count
        if pos != flat.size:
            raise ValueError("weight count %d != expected %d" % (flat.size, pos))

    def flat_gradients(self):
        parts = []
        for tensor, transpose in self.flat_parameters():
            grad = tensor.grad if tensor.grad is not None else torch.zeros_like(tensor)
            parts.append((grad.t() if transpose else grad).contiguous().reshape(-1))
        return torch.cat(parts)


def aggregation_matrix(adjacency, kind):
    degree = adjacency.sum(dim=1)
    if kind == "symmetric":
        inv_sqrt = torch.where(degree > 0, degree.clamp(min=1e-30).rsqrt(),
                               torch.zeros_like(degree))
        return inv_sqrt[:, None] * adjacency * inv_sqrt[None, :]
    if kind == "row":
        inv = torch.where(degree > 0, 1.0 / degree.clamp(min=1e-30),
                          torch.zeros_like(degree))
        return inv[:, None] * adjacency
    raise ValueError("unknown aggregation " + kind)


def read_meta(path):
    meta = {}
    with open(path) as f:
        for line in f:
            parts = line.split()
            if parts:
                meta[parts[0]] = parts[1:]
    return meta


def load(directory, name, dtype=np.float32):
    return np.fromfile(os.path.join(directory, name), dtype=dtype)


def run_check(directory):
    torch.set_default_dtype(torch.float64)
    meta = read_meta(os.path.join(directory, "meta.txt"))
    input_dim = int(meta["input_dim"][0])
    gcn_dims = [int(v) for v in meta["gcn_dims"]]
    fc_dim = int(meta["fc_dim"][0])
    aggregation = meta["aggregation"][0]
    positive_weight = float(meta["positive_weight"][0])
    num_graphs = int(meta["num_graphs"][0])

    model = Gcn(input_dim, gcn_dims, fc_dim)
    model.load_flat(load(directory, "weights.bin").astype(np.float64))
    norm = load(directory, "norm.bin").astype(np.float64).reshape(2, input_dim)
    shift = torch.from_numpy(norm[0])
    scale = torch.from_numpy(norm[1])

    model.zero_grad()
    total_loss = 0.0
    for g in range(num_graphs):
        n, n1 = (int(v) for v in meta["graph%d" % g])
        raw = torch.from_numpy(
            load(directory, "features_%d.bin" % g).astype(np.float64)
        ).reshape(n, input_dim)
        adjacency = torch.from_numpy(
            load(directory, "adjacency_%d.bin" % g).astype(np.float64)
        ).reshape(n, n)
        labels = torch.from_numpy(
            load(directory, "labels_%d.bin" % g).astype(np.float64))
        x = (raw - shift) * scale
        logits = model(x, aggregation_matrix(adjacency, aggregation), n1)
        loss = F.binary_cross_entropy_with_logits(
            logits, labels, pos_weight=torch.tensor(positive_weight),
            reduction="sum")
        loss.backward()
        total_loss += float(loss)
        logits.detach().numpy().astype(np.float64).tofile(
            os.path.join(directory, "out_logits_%d.bin" % g))
    model.flat_gradients().detach().numpy().astype(np.float64).tofile(
        os.path.join(directory, "out_grads.bin"))
    np.array([total_loss], dtype=np.float64).tofile(
        os.path.join(directory, "out_loss.bin"))
    print("ok: %d graph(s), loss %.6f" % (num_graphs, total_loss))


def run_bench(args):
    torch.set_num_threads(args.threads)
    torch.manual_seed(0)
    model = Gcn(args.dim, [512, 512, 256, 256], 256).eval()
    n, n1 = args.nodes, args.one_hop
    x = torch.randn(1, n, args.dim)
    # Random symmetric adjacency with about 2u neighbours per node.
    a = (torch.rand(n, n) < (2.0 * args.u / n)).float()
    a = ((a + a.t()) > 0).float()
    a.fill_diagonal_(0)
    g = aggregation_matrix(a, "symmetric")[None]
    with torch.no_grad():
        for _ in range(3):
            model(x, g, n1)
        start = time.perf_counter()
        cpu_start = time.process_time()
        for _ in range(args.iterations):
            model(x, g, n1)
        seconds = (time.perf_counter() - start) / args.iterations
        cpu_seconds = (time.process_time() - cpu_start) / args.iterations
    print("torch %s, %d thread(s): QES n=%d (1-hop %d), D=%d: %.3f ms per "
          "query wall, %.3f ms CPU"
          % (torch.__version__, torch.get_num_threads(), n, n1, args.dim,
             seconds * 1e3, cpu_seconds * 1e3))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="mode", required=True)
    check = sub.add_parser("check")
    check.add_argument("directories", nargs="+")
    bench = sub.add_parser("bench")
    bench.add_argument("--nodes", type=int, default=600)
    bench.add_argument("--one_hop", type=int, default=100)
    bench.add_argument("--dim", type=int, default=256)
    bench.add_argument("--u", type=int, default=5)
    bench.add_argument("--threads", type=int, default=1)
    bench.add_argument("--iterations", type=int, default=20)
    args = parser.parse_args()
    if args.mode == "check":
        for directory in args.directories:
            run_check(directory)
    else:
        run_bench(args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
