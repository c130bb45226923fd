// screen.vert: one triangle covering the viewport (draw 3 vertices, no attributes); screen
// passes are limited to the pixels that matter by the scissor box.
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
