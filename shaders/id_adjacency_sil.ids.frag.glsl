// Adjacency SIL, ID pass, fragment stage: the nearest triangle's ID (depth test) per pixel.
flat in uint g_id;
layout(location = 0) out uint o_id;

void main() { o_id = g_id; }
