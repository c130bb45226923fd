// common.glsl: shared by every slice shader. Pixel states (values equal vsil::PixelState,
// checked by tests/slicing) and the sample position of a pixel on the current slice plane.
#define STATE_EMPTY 0
#define STATE_FILLED 1
#define STATE_CONTOUR 2
#define STATE_SILHOUETTE 3
