"""The scene as the kernels take it: the net's geometry and springs, the opening, the static
model, the net's modes and stable steps, and families of nets drawn per episode."""
