// Implemented by the geometry work (geometry.h).
