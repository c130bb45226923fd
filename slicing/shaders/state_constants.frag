// state_constants.frag: writes the four STATE_* constants (hit_records.glsl) into pixels 0..3 of
// an R8UI target, so a test can check them against vsil::PixelState.
layout(location = 0) out uint value;

void main() {
  const uint states[4] = uint[4](STATE_EMPTY, STATE_FILLED, STATE_CONTOUR, STATE_SILHOUETTE);
  value = states[min(int(gl_FragCoord.x), 3)];
}
