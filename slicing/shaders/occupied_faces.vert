// occupied_faces.vert: the boundary faces of occupied bricks (slicing/empty_space.h), in voxel
// coordinates, with their own transform (the frame's uniform block need not be bound).
layout(location = 0) in vec3 positionVoxel;
uniform mat4 facesClipFromVoxel;

void main() { gl_Position = facesClipFromVoxel * vec4(positionVoxel, 1.0); }
