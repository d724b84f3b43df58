"""DeepCFD-style U-Net (Ribeiro et al. 2020) for plume mean and std, as in
docs/design/surrogate.md, "Architecture".

Wiring (the same as DeepCFD's UNetEx with weight and batch norm off):
  encoder level b = 0..L-1: `convs` convolutions (kernel k, padding k//2, ReLU) to filters[b] channels,
      the output is kept as the skip of level b, then 2x2 max-pool keeping the argmax indices;
  one decoder per output, deepest level first, b = L-1..0: max-unpool with level b's indices to the
      skip's size, concatenate [skip, unpooled] on channels, then `convs` stride-1 transposed
      convolutions: 2*filters[b] -> filters[b] -> ... -> filters[b-1] (1 at level 0);
      ReLU after each, except the network's very last layer.
With 3 inputs, 2 outputs, filters 8,16,32,32, kernel 5 and 3 convolutions a block: 600,130 parameters.
"""
import torch
import torch.nn as nn
import torch.nn.functional as F

REAL_FILTERS = (8, 16, 32, 32)
REAL_KERNEL = 5
REAL_CONVS = 3
REAL_PARAMETERS = 600130


class PlumeUNet(nn.Module):
    def __init__(self, in_channels=3, out_channels=2, filters=REAL_FILTERS, kernel=REAL_KERNEL,
                 convs=REAL_CONVS, residual_channel=None, residual_factor=1.0):
        super().__init__()
        # A residual model (issue 46): output 0 (the mean) is the network's plus residual_factor
        # times input channel residual_channel (the physics plume; the factor is its input scale
        # over the mean's output scale, 1 as train.py scales both). Not a weight, so the state
        # dict and the model file's tensors are the plain network's.
        self.residual_channel, self.residual_factor = residual_channel, float(residual_factor)
        assert kernel % 2 == 1 and len(filters) > 0 and convs > 0
        self.in_channels = in_channels
        self.out_channels = out_channels
        self.filters = tuple(filters)
        self.kernel = kernel
        self.padding = kernel // 2
        self.convs = convs

        self.encoder = nn.ModuleList()
        prev = in_channels
        for f in self.filters:
            self.encoder.append(nn.ModuleList(
                nn.Conv2d(prev if j == 0 else f, f, kernel, padding=self.padding)
                for j in range(convs)))
            prev = f

        # decoders[o][b]: output o, level b (0 = finest); run from b = L-1 down to 0.
        self.decoders = nn.ModuleList()
        for _ in range(out_channels):
            levels = nn.ModuleList()
            for b, f in enumerate(self.filters):
                last_out = self.filters[b - 1] if b > 0 else 1
                levels.append(nn.ModuleList(
                    nn.ConvTranspose2d(2 * f if j == 0 else f, last_out if j == convs - 1 else f,
                                       kernel, padding=self.padding)
                    for j in range(convs)))
            self.decoders.append(levels)

    def layer_table(self):
        """(name, op, module, relu) in execution order: the order of the tensors in the model file."""
        rows = []
        for b, block in enumerate(self.encoder):
            for j, conv in enumerate(block):
                rows.append((f"encoder.{b}.{j}", "conv2d", conv, True))
        for o, levels in enumerate(self.decoders):
            for b in reversed(range(len(levels))):
                for j, conv in enumerate(levels[b]):
                    final = b == 0 and j == self.convs - 1
                    rows.append((f"decoder.{o}.{b}.{j}", "conv_transpose2d", conv, not final))
        return rows

    def forward(self, x):
        inputs = x
        skips, indices = [], []
        for block in self.encoder:
            for conv in block:
                x = F.relu(conv(x))
            skips.append(x)
            x, ind = F.max_pool2d(x, 2, 2, return_indices=True)
            indices.append(ind)
        outputs = []
        for levels in self.decoders:
            y = x
            for b in reversed(range(len(levels))):
                y = F.max_unpool2d(y, indices[b], 2, 2, output_size=skips[b].shape[-2:])
                y = torch.cat([skips[b], y], dim=1)
                for j, conv in enumerate(levels[b]):
                    y = conv(y)
                    if not (b == 0 and j == self.convs - 1):
                        y = F.relu(y)
            outputs.append(y)
        if self.residual_channel is not None:
            c = self.residual_channel
            outputs[0] = outputs[0] + self.residual_factor * inputs[:, c:c + 1]
        return torch.cat(outputs, dim=1)


def parameter_count(model):
    return sum(p.numel() for p in model.parameters())


def pick_device():
    """CUDA when present (a recent PyTorch on a GPU machine), else the CPU."""
    return torch.device("cuda" if torch.cuda.is_available() else "cpu")


if __name__ == "__main__":
    print(parameter_count(PlumeUNet()))


def pool_margin(model, x, ignore_exact_ties=False):
    """Per sample, the smallest margin of any 2x2 max-pool decision, relative to that level's
    largest |pre-activation|, computed in float64. A window is decided by max(v1 - v2, -z_max): the
    gap between its two largest post-ReLU values, or how far below zero all its pre-activations
    are (then every value is an exact 0 and the first wins). Float32 engines that sum in different
    orders agree on every argmax, and so within rounding everywhere, when this is well above
    float32's accumulated rounding (~1e-6 for these layers); below it, max-unpool may move a value.
    ignore_exact_ties: windows decided by exactly 0 do not count. Such a tie in float64 comes from
    bit-identical computations (v2's zero padding: every column of a row of it computes the same
    values), which every engine breaks alike, to the first; otherwise every padded sample scores 0."""
    m64 = PlumeUNet(model.in_channels, model.out_channels, model.filters, model.kernel, model.convs)
    m64.load_state_dict(model.state_dict())
    m64 = m64.double().eval()
    h = torch.as_tensor(x).double()
    margin = torch.full((h.shape[0],), float("inf"), dtype=torch.float64)
    with torch.no_grad():
        for block in m64.encoder:
            for j, conv in enumerate(block):
                z = conv(h)
                h = F.relu(z)
            n, c, rows, cols = z.shape
            pr, pc = rows // 2, cols // 2

            def windows(t):
                t = t[..., :2 * pr, :2 * pc].reshape(n, c, pr, 2, pc, 2)
                return t.permute(0, 1, 2, 4, 3, 5).reshape(n, c, pr, pc, 4)

            v = torch.sort(windows(h), dim=-1, descending=True).values
            z_max = windows(z).max(dim=-1).values
            decided = torch.maximum(v[..., 0] - v[..., 1], -z_max)
            if ignore_exact_ties:
                decided = torch.where(decided == 0, torch.full_like(decided, float("inf")), decided)
            scale = z.abs().reshape(n, -1).max(dim=1).values.clamp_min(1e-300)
            margin = torch.minimum(margin, decided.reshape(n, -1).min(dim=1).values / scale)
            h = F.max_pool2d(h, 2, 2)
    return margin.numpy()
