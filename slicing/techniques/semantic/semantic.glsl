// semantic.glsl: what the rule compiler's generated code (rule_compiler.h) calls, before it in
// the program: the membership-function and defuzzification tables and the normalized inputs.
// A table of `size` entries a row (entry k at x = k / (size − 1)) is a texture of its size − 1
// segments: texel k holds entries k and k + 1 (semantic_technique.cpp tableSegments), read with
// one texelFetch and a mix; not GL_LINEAR, whose 8-bit filter weights would cost precision.
// One fetch instead of two took a 16-rule frame from 570–597 to 456–513 ms (bonsai, 512²).

layout(binding = UNIT_AUXILIARY0) uniform sampler2D membershipTable;  // RG32F, a row per value
layout(binding = UNIT_AUXILIARY1) uniform sampler2D defuzzTable;      // RGBA32F (N, D) twice

// The normalized sources (rule_compiler.h), set by semantic.frag where the rules use them.
float semanticData, semanticGradient, semanticCursorDistance, semanticPlaneDistance,
    semanticImageDistance, semanticViewAngle, semanticTime;

// The segment of a row holding x (clamped to [0, 1]) in a table of `segments` segments a row,
// and x's place in it, `f` in [0, 1] (MembershipTables::at computes the same on the CPU).
int tableSegment(int segments, float x, out float f) {
  float t = clamp(x, 0.0, 1.0) * float(segments);
  int k = min(int(t), segments - 1);
  f = t - float(k);
  return k;
}

float semanticMembership(int row, float x) {
  float f;
  int k = tableSegment(textureSize(membershipTable, 0).x, x, f);
  vec2 ends = texelFetch(membershipTable, ivec2(k, row), 0).rg;
  return mix(ends.x, ends.y, f);
}

// (N(a), D(a)) of a consequent value's row at the rule degree a (core/rules.h DefuzzTables).
vec2 semanticDefuzz(int row, float degree) {
  float f;
  int k = tableSegment(textureSize(defuzzTable, 0).x, degree, f);
  vec4 ends = texelFetch(defuzzTable, ivec2(k, row), 0);
  return mix(ends.xy, ends.zw, f);
}
