"""Pictures of a simulation: the NumPy rasteriser and its camera, GIF/MP4/HTML films, 3D
snapshots and the replay page."""
