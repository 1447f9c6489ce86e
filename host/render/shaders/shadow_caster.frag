// Depth only: the rasteriser's interpolated depth plus glPolygonOffset, stored in the format.
void main() {}
