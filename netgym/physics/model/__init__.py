"""The scene as the kernels take it: the net's geometry, the opening, the contact tables and the
static model with its state."""
