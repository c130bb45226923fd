// semantic.frag: technique `semantic`'s slice pass, the template the generated rule code
// (rule_compiler.h) is compiled into (semantic_technique.h). Per sample: the sources the rules
// use (normalized to [0, 1]), the rules (semanticEvaluate), then the artistic template: each
// style's defuzzified value picks a sphere of its lit-sphere ramp and the eye-space normal a
// texel of it (sphere_atlas.h); the styles are layered bottom to top (priority, then declaration
// order), each over the ones below with opacity weight·α; the result is composited front to back
// with the opacity correction of shaders/compositing.glsl.
// Without SEMANTIC_FLAT: out (c·α, α), blended behind what is there (compositing.h).
// With SEMANTIC_FLAT (the flat rendering mode, Rautek et al. section 5.2): no output; the colour
// and the highest priority met so far are updated in place (images), and on entering a region
// of higher priority the colour so far is scaled by 1 − p_f.
// With SEMANTIC_PLANE_SHOW: samples within half a voxel of the plane show the data as grey.
// In: the volume, its gradient texture (shaders/gradients.glsl), the tables (semantic.glsl), the
// sphere atlas (UNIT_AUXILIARY2), the visible data intervals (UNIT_AUXILIARY3).

#ifdef SEMANTIC_FLAT
layout(early_fragment_tests) in;
layout(binding = IMAGE_RECORD, rgba32f) uniform coherent image2D colorImage;
layout(binding = IMAGE_AUXILIARY0, r32f) uniform coherent image2D priorityImage;
uniform float globalFlatness;  // --flatness, or < 0: the flatness rules'
uniform float terminationOpacity;
#else
layout(location = 0) out vec4 result;
#endif

layout(binding = UNIT_AUXILIARY2) uniform sampler3D sphereAtlas;
layout(binding = UNIT_AUXILIARY3) uniform sampler2D visibleIntervals;  // R32F, 1 row
uniform float valueMin, valueScale;  // data = (value − valueMin)·valueScale
uniform mat3 worldFromEye, eyeFromWorld;
uniform int styleOrder[SEMANTIC_STYLE_COUNT];  // bottom to top
uniform float stylePriority[SEMANTIC_STYLE_COUNT];
uniform float sphereFirst[SEMANTIC_STYLE_COUNT];  // its first layer in the atlas
uniform float sphereSpan[SEMANTIC_STYLE_COUNT];   // its sphere count − 1
uniform float atlasDepth;
uniform vec3 voxelSpacing;  // physical size of a voxel
uniform float inverseDiagonal;  // 1 / |dims·spacing|
uniform vec3 cursorPhysical;
uniform vec3 planePointPhysical, planeNormal;  // unit normal, physical axes
uniform float planeHalfThickness;
uniform vec2 cursorWindow;  // the cursor pixel's centre in window coordinates
uniform float inverseImageDiagonal;
uniform float timeValue;
// The highest priority of any style, one above with SEMANTIC_PLANE_SHOW: the plane's.
uniform float topPriority;

void main() {
  vec3 voxel = sliceVoxel();
  // The pieces overlap across brick borders (slicer.h slicePieces): the owner draws a sample.
  if (!insideVolume(voxel) || !ownedByBrick(voxel)) discard;
#ifdef SEMANTIC_FLAT
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 dst = imageLoad(colorImage, pixel);
  float top = imageLoad(priorityImage, pixel).r;
  // Nothing behind can show any more: opaque, and no higher priority left to enter.
  if (dst.a >= terminationOpacity && top >= topPriority) discard;
#endif
  vec4 fetched;
  float value = sampleValue(voxel, fetched);
  float data = clamp((value - valueMin) * valueScale, 0.0, 1.0);
  vec3 physical = voxel * voxelSpacing;
#ifdef SEMANTIC_PLANE_SHOW
  bool onPlane = abs(dot(physical - planePointPhysical, planeNormal)) <= planeHalfThickness;
#else
  const bool onPlane = false;
#endif
  {
    // No rule can give this data value any opacity (visibleDataIntervals).
    int size = textureSize(visibleIntervals, 0).x + 1;
    int k = min(int(data * float(size - 1)), size - 2);
    if (!onPlane && texelFetch(visibleIntervals, ivec2(k, 0), 0).r <= 0.0) discard;
  }
  vec3 direction;
  float gradientMagnitude;
  splitGradient(gradientAt(voxel, fetched), direction, gradientMagnitude);

  semanticData = data;
  semanticGradient = gradientMagnitude;
#ifdef SEMANTIC_SOURCE_CURSOR_DISTANCE
  semanticCursorDistance = length(physical - cursorPhysical) * inverseDiagonal;
#endif
#ifdef SEMANTIC_SOURCE_PLANE_DISTANCE
  semanticPlaneDistance = abs(dot(physical - planePointPhysical, planeNormal)) * inverseDiagonal;
#endif
#ifdef SEMANTIC_SOURCE_IMAGE_DISTANCE
  semanticImageDistance = length(gl_FragCoord.xy - cursorWindow) * inverseImageDiagonal;
#endif
#ifdef SEMANTIC_SOURCE_VIEW_ANGLE
  {
    vec3 toViewerEye = orthographic != 0 ? vec3(0.0, 0.0, 1.0)
                                         : -normalize(eyePointAt(sliceEyeDistance));
    // The angle between ∇f and the viewing direction, over 180°: 0 where the surface of a
    // denser region faces the viewer, 0.5 edge-on (and where ∇f vanishes).
    float c = clamp(dot(direction, -(worldFromEye * toViewerEye)), -1.0, 1.0);
    semanticViewAngle = acos(c) * (1.0 / 3.14159265358979);
  }
#endif
  semanticTime = timeValue;

  float weight[SEMANTIC_STYLE_COUNT], styleValue[SEMANTIC_STYLE_COUNT];
  vec2 flatness;
  semanticEvaluate(weight, styleValue, flatness);

  // The outward normal (−∇f) in eye space picks the texel of each sphere.
  vec2 uv = 0.5 + 0.5 * (eyeFromWorld * -direction).xy;
  vec4 layers = vec4(0.0);  // premultiplied, bottom to top
  float samplePriority = -1e30, strongest = 0.0;
  for (int i = 0; i < SEMANTIC_STYLE_COUNT; ++i) {
    int s = styleOrder[i];
    if (weight[s] <= 0.0) continue;
    float z = (sphereFirst[s] + styleValue[s] * sphereSpan[s] + 0.5) / atlasDepth;
    vec4 c = texture(sphereAtlas, vec3(uv, z));
    float a = weight[s] * c.a;
    layers = vec4(c.rgb * a, a) + layers * (1.0 - a);
    // The region a sample belongs to: the style that gives it the most opacity (ties: the upper).
    if (a > 0.0 && a >= strongest) {
      strongest = a;
      samplePriority = stylePriority[s];
    }
  }
  if (onPlane) {
    layers = vec4(vec3(data), 1.0);
    samplePriority = topPriority;
  }
  if (layers.a <= 0.0) discard;
  vec4 src = compositedSample(layers.rgb / layers.a, layers.a);
#ifdef SEMANTIC_FLAT
  if (samplePriority > top) {
    // c_r(x_i) = c_r(x_{i−1})·(1 − p_f) on entering a region of higher priority.
    float pf = globalFlatness >= 0.0 ? globalFlatness : flatness.y;
    dst *= 1.0 - clamp(pf, 0.0, 1.0);
    imageStore(priorityImage, pixel, vec4(samplePriority));
  }
  imageStore(colorImage, pixel, dst + (1.0 - dst.a) * src);
#else
  result = src;
#endif
}
