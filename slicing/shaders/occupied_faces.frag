// occupied_faces.frag: the boundary faces of occupied bricks (slicing/empty_space.h).
// Into a depth buffer, faces leave only depth (entry faces, kept by the depth test LESS). With
// DEPTH_AS_COLOR the fragment's window depth goes out as colour: exit faces kept by MAX
// blending, or entry faces kept by MIN blending for passes that read the entry depth as a
// texture (the tile march).
#ifdef DEPTH_AS_COLOR
layout(location = 0) out float faceDepth;

// Depth clamping keeps faces beyond the far plane; their depth is clamped here as it is for
// the depth buffer.
void main() { faceDepth = clamp(gl_FragCoord.z, 0.0, 1.0); }
#else
void main() {}
#endif
