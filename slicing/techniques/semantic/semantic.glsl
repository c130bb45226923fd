// semantic.glsl: what the rule compiler's generated code (rule_compiler.h) calls, before it in
// the program: the membership-function and defuzzification tables and the normalized inputs.
// Tables are read with two texelFetch and a mix, not GL_LINEAR (whose 8-bit filter weights
// would cost precision): entry k at x = k / (size − 1).

layout(binding = UNIT_AUXILIARY0) uniform sampler2D membershipTable;  // R32F, a row per value
layout(binding = UNIT_AUXILIARY1) uniform sampler2D defuzzTable;      // RG32F (N, D), a row each

// The normalized sources (rule_compiler.h), set by semantic.frag where the rules use them.
float semanticData, semanticGradient, semanticCursorDistance, semanticPlaneDistance,
    semanticImageDistance, semanticViewAngle, semanticTime;

float semanticMembership(int row, float x) {
  int size = textureSize(membershipTable, 0).x;
  float t = clamp(x, 0.0, 1.0) * float(size - 1);
  int k = min(int(t), size - 2);
  float f = t - float(k);
  return mix(texelFetch(membershipTable, ivec2(k, row), 0).r,
             texelFetch(membershipTable, ivec2(k + 1, row), 0).r, f);
}

// (N(a), D(a)) of a consequent value's row at the rule degree a (core/rules.h DefuzzTables).
vec2 semanticDefuzz(int row, float degree) {
  int size = textureSize(defuzzTable, 0).x;
  float t = clamp(degree, 0.0, 1.0) * float(size - 1);
  int k = min(int(t), size - 2);
  float f = t - float(k);
  return mix(texelFetch(defuzzTable, ivec2(k, row), 0).rg,
             texelFetch(defuzzTable, ivec2(k + 1, row), 0).rg, f);
}
