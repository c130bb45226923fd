// occupied_faces.frag: the boundary faces of occupied bricks (slicing/empty_space.h).
// Entry faces (towards the eye) leave only depth, kept by the depth test LESS. With EXIT_DEPTH
// (faces turned away) the fragment's window depth goes out as colour, kept by MAX blending.
#ifdef EXIT_DEPTH
layout(location = 0) out float exitDepth;

// Depth clamping keeps faces beyond the far plane; their depth is clamped here as it is for
// the depth buffer.
void main() { exitDepth = clamp(gl_FragCoord.z, 0.0, 1.0); }
#else
void main() {}
#endif
