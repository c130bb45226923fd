// illustrate_sample.glsl: one sample of illustrate (illustrate_technique.h), for both of its
// pipelines: the slice pass (composite.frag) and the tile march (march.comp). A sample is
// classified by the transfer function, enhanced by the effects the program was built with
// (#defines BOUNDARY, SILHOUETTE, FADING, SKETCH, DISTANCE, HALO, TONE; the formulas in
// shaders/illustration.glsl), shaded, and made premultiplied and corrected for the slice distance
// (shaders/compositing.glsl). In: the volume, its gradient texture (shaders/gradients.glsl:
// ∇f/max|∇f| in world axes, with the values where it holds them), the transfer function
// (TRANSFER_TABLE: a 1D texture over the data's range; otherwise the paper's power function over
// one colour), with HALO the halo mask (halo_mask.h; HALO_FIELD: the halo field instead, per
// brick).
// SKIP_SAMPLE is what a sample that adds nothing does, as early as that is known: the slice pass
// discards it (llvmpipe leaves a block of fragments once all of them are discarded), the march
// returns false and goes on with its next slice.
// The slice pass's vertex stage gets the shared sources too; it needs none of this.
#ifndef VSIL_VERTEX_SHADER
#ifndef SKIP_SAMPLE
#error "illustrate_sample.glsl needs SKIP_SAMPLE (illustrate_technique.cpp)"
#endif

uniform mat3 worldFromEye;  // rotation: eye-space directions into the gradients' axes
// Samples at or below this value are transparent (the transfer function is 0 up to it): they
// leave before classification. llvmpipe leaves a block of fragments once all of them are
// discarded, so transparent space costs one volume sample.
uniform float transparentBelow;

#ifdef TRANSFER_TABLE
layout(binding = UNIT_TRANSFER_FUNCTION) uniform sampler1D transferTable;
uniform vec2 tableCoordFromValue;  // texture coordinate = value·x + y
#else
uniform float valueMin, valueScale;  // v = (value − valueMin)·valueScale in [0, 1]
uniform vec3 sampleColor;
uniform float k_os, k_oe;
#endif

// Straight colour and opacity per voxel of a sample value (data units).
vec4 classify(float value) {
#ifdef TRANSFER_TABLE
  return texture(transferTable, value * tableCoordFromValue.x + tableCoordFromValue.y);
#else
  float v = clamp((value - valueMin) * valueScale, 0.0, 1.0);
  return vec4(sampleColor, k_os * pow(v, k_oe));
#endif
}

#if defined(HALO) && defined(HALO_FIELD)
// Feature halos from the halo field (halo_mask.h haloFieldVoxels, halo_mode=field): per voxel
// F (the neighbours' pushes towards it, summed once per volume over its 3D neighbourhood) and
// N (their mean outward normal). h = F·(1 − |N·V|)^k_hse·(1 − |∇f(P_i)|): one fetch of the
// sample's nearest voxel instead of the exact mode's taps. Alpha 0 marks "no halo and
// transparent": those samples leave before the volume fetch.
layout(binding = UNIT_AUXILIARY0) uniform sampler3D haloMask;
uniform float k_hse;

// The voxel nearest to a voxel position (what GL_NEAREST picks), clamped to the volume, as a
// texel of this piece's brick (the field has the volume texture's layout).
ivec3 nearestBrickTexel(vec3 voxel) {
  return clamp(ivec3(floor(voxel + 0.5)), ivec3(0), ivec3(volumeDims) - 1) - ivec3(brickOrigin);
}

float haloFromField(vec4 field, vec3 v, float gradientMagnitude) {
  float strength = max(field.a * 255.0 - 1.0, 0.0) / (254.0 * HALO_FIELD_SCALE);
  vec3 n = (field.rgb * 255.0 - 128.0) / 127.0;
  return strength * pow(max(1.0 - abs(dot(n, v)), 0.0), k_hse) * (1.0 - gradientMagnitude);
}
#elif defined(HALO)
// Feature halos from a neighbourhood in the slice plane (halos lie mostly in planes across the
// view): HALO_TAPS taps at offsets within k_hr voxels, the nearest texel of the gradients each.
// A tap's potential is the paper's h_n = (n_n·d)^k_hpe·(1 − |n_n·V|)^k_hse, d the unit direction
// from the tap to the sample and n_n its outward normal, weighted by its gradient magnitude (the
// paper: "a large gradient in the direction of this sample"). h = Σ w_n h_n·(1 − |∇f(P_i)|),
// w_n ∝ 1/|P_i − P_n|² summing to 1, so h is in [0, 1]. Halos surround visible features only:
// h counts where the halo mask (halo_mask.h) marks the sample's voxel as near one, which also
// lets the samples far from every feature leave early and keeps halos inside the occupancy
// margin of empty-space skipping.
layout(binding = UNIT_AUXILIARY0) uniform sampler3D haloMask;
uniform vec3 haloOffsets[HALO_TAPS];     // voxel offsets, in the slice plane
uniform vec3 haloDirections[HALO_TAPS];  // world, unit: from the tap towards the sample
uniform float haloWeights[HALO_TAPS];
uniform float k_hpe, k_hse;

// The voxel nearest to a voxel position (what GL_NEAREST picks), clamped to the volume. Halos
// need the volume in one brick (origin 0; illustrate_technique.cpp refuses more), so it is
// also the texel of the gradient texture and the halo mask.
ivec3 nearestTexel(vec3 voxel) {
  return clamp(ivec3(floor(voxel + 0.5)), ivec3(0), ivec3(volumeDims) - 1);
}

float haloSize(vec3 voxel, vec3 v, float gradientMagnitude) {
  float h = 0.0;
  for (int k = 0; k < HALO_TAPS; ++k) {
    vec3 direction;
    float magnitude;
    splitGradient(texelFetch(gradientTexture, nearestTexel(voxel + haloOffsets[k]), 0).xyz,
                  direction, magnitude);
    vec3 n = -direction;
    float towards = max(dot(n, haloDirections[k]), 0.0);
    float across = max(1.0 - abs(dot(n, v)), 0.0);
    h += haloWeights[k] * magnitude * pow(towards, k_hpe) * pow(across, k_hse);
  }
  return h * (1.0 - gradientMagnitude);
}
#endif

// True where the sample at a voxel position surely adds nothing, known with the fewest fetches
// (illustratedSample skips every such sample): the march passes over a ray's leading
// transparent samples with this test alone.
bool addsNothing(vec3 voxel) {
#ifdef HALO_FIELD
  return texelFetch(haloMask, nearestBrickTexel(voxel), 0).a <= 0.0;
#else
  vec4 fetched;
  float value = sampleValue(voxel, fetched);
#ifdef HALO
  return value <= transparentBelow && texelFetch(haloMask, nearestTexel(voxel), 0).r <= 0.0;
#else
  return value <= transparentBelow;
#endif
#endif
}

// The sample at a (quantized) voxel position of a pixel at `ndc`, on the slice at `eyeDistance`
// (−z_eye) and normalized depth `depth`: premultiplied (c·α, α) into `premultiplied`, true; or
// SKIP_SAMPLE where it is transparent.
bool illustratedSample(vec3 voxel, vec2 ndc, float eyeDistance, float depth,
                       out vec4 premultiplied) {
#ifdef HALO_FIELD
  vec4 haloField = texelFetch(haloMask, nearestBrickTexel(voxel), 0);
  if (haloField.a <= 0.0) SKIP_SAMPLE;  // no halo, and transparent whatever the volume holds
  float nearFeature = haloField.a > 1.5 / 255.0 ? 1.0 : 0.0;  // F > 0
#endif
  vec4 fetched;
  float value = sampleValue(voxel, fetched);
#ifdef HALO
#ifndef HALO_FIELD
  float nearFeature = texelFetch(haloMask, nearestTexel(voxel), 0).r;
#endif
  if (value <= transparentBelow && nearFeature <= 0.0) SKIP_SAMPLE;
  vec4 material = classify(value);
  if (material.a <= 0.0 && nearFeature <= 0.0) SKIP_SAMPLE;
#else
  // A transparent sample adds nothing (and, unless the value came with it, costs no gradient).
  if (value <= transparentBelow) SKIP_SAMPLE;
  vec4 material = classify(value);
  if (material.a <= 0.0) SKIP_SAMPLE;
#endif
  vec3 direction;
  float gradientMagnitude;
  bool hasDirection = splitGradient(gradientAt(voxel, fetched), direction, gradientMagnitude);
  vec3 n = -direction;  // outward
  vec3 toViewerEye = orthographic != 0 ? vec3(0.0, 0.0, 1.0)
                                       : -normalize(eyePointAtNdc(ndc, eyeDistance));
  vec3 v = worldFromEye * toViewerEye;
  // A vanishing gradient has no direction: it counts as facing the viewer (as in common.glsl),
  // so flat regions get no silhouette, sketch or fading of their own.
  float facing = hasDirection ? abs(dot(n, v)) : 1.0;

  float opacity = material.a;
  vec3 base = material.rgb;
#ifdef BOUNDARY
  opacity = boundaryOpacity(opacity, gradientMagnitude);
#endif
#ifdef SILHOUETTE
  opacity = silhouetteOpacity(opacity, facing);
#endif
#ifdef FADING
  orientedFading(base, opacity, facing);
#endif
  vec3 color = litColor(base, n);
#ifdef TONE
  color = toneShade(color, base, n);
#endif
#ifdef SKETCH
  sketchLines(color, opacity, facing, gradientMagnitude);
#endif
#ifdef DISTANCE
  color = distanceBlend(color, depth);
#endif
#if defined(HALO) && defined(HALO_FIELD)
  featureHalo(color, opacity, haloFromField(haloField, v, gradientMagnitude));
#elif defined(HALO)
  float h = haloSize(voxel, v, gradientMagnitude) * nearFeature;
  featureHalo(color, opacity, h);
#endif
  premultiplied = compositedSample(color, opacity);
  return true;
}

#endif  // VSIL_VERTEX_SHADER
