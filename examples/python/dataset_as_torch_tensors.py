#!/usr/bin/python3
"""A plumekit dataset as torch tensors.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/dataset_as_torch_tensors.py [DATASET]

Without DATASET, makes a small one first with the command line (`plumekit dataset generate`,
2 random maps x 4 sources, advection-diffusion: seconds). plumekit.read_dataset checks every shard
against its checksums; torch.from_numpy then shares the arrays' memory.
"""
import os
import subprocess
import sys
from pathlib import Path

import torch

import plumekit

if len(sys.argv) > 1:
    folder = Path(sys.argv[1])
else:
    folder = Path("out/python/dataset")
    exe = os.environ.get("PLUMEKIT_EXE", "build/plumekit")
    subprocess.run([exe, "dataset", "generate", "--maps", "2", "--sources", "4", "--seed", "7",
                    "--simulator", "advection-diffusion", "--out", str(folder)], check=True)

data = plumekit.read_dataset(folder)
inputs = torch.from_numpy(data["inputs"])  # [n, 3, 64, 64]: labels, signed distance, source
targets = torch.from_numpy(data["targets"])  # [n, 2, 64, 64]: mean and std concentration
print(f"{folder}: {inputs.shape[0]} samples from {len(set(data['map_ids'].tolist()))} maps, "
      f"seed {data['parameters']['seed']}")
print(f"inputs {tuple(inputs.shape)} {inputs.dtype}, targets {tuple(targets.shape)}")
loader = torch.utils.data.DataLoader(torch.utils.data.TensorDataset(inputs, targets),
                                     batch_size=4, shuffle=True,
                                     generator=torch.Generator().manual_seed(0))
x, y = next(iter(loader))
print(f"a batch: {tuple(x.shape)} -> {tuple(y.shape)}, mean concentration peak "
      f"{y[:, 0].amax().item():.0f}")
