// illustration.glsl: the Ebert–Rheingans formulas (IEEE Vis 2000), once, for every pass that
// applies them: illustrate's slice pass (techniques/illustrate/composite.frag) and the tone fill
// of the pixel-state techniques (tone_fill.frag, slicing/tone_fill.h). Parameters are uniforms
// named as in the paper (src/core/illustration.h lists them with defaults and ranges), so
// changing one never recompiles; which effects run is decided by the caller's #defines. The CPU
// references (tests/reference/illustration_formulas.h) write every formula again.
//
// All vectors in one space (world axes for illustrate, eye space for the tone fill): n the
// outward unit normal, −∇f/|∇f| (the paper's "gradient" is the surface normal, which points out
// of the denser side: data that is denser inside its features, as CT and most simulations are),
// 0 where the gradient vanishes; v towards the viewer; the lights' directions towards the lights.

// LIGHT_COUNT, the number of lights, is a #define (slicing/illustration_options.h
// lightCountDefine) so that the loops over the lights unroll: llvmpipe runs a loop to a uniform
// count as a masked loop, which cost illustrate's plain composite about a tenth of its frame.
#ifndef LIGHT_COUNT
#error "illustration.glsl needs LIGHT_COUNT (illustration_options.h lightCountDefine)"
#endif
uniform vec3 lightDirections[LIGHT_COUNT];

// The plain lit colour, the paper's I_G: ambient plus diffuse from every light.
uniform float k_a, k_d;
vec3 litColor(vec3 color, vec3 n) {
  float diffuse = 0.0;
  for (int i = 0; i < LIGHT_COUNT; ++i) diffuse += max(dot(n, lightDirections[i]), 0.0);
  return color * (k_a + k_d * diffuse);
}

// Boundary enhancement: o_g = o_v·(k_gc + k_gs·|∇f|^k_ge), |∇f| normalized by the volume's largest.
uniform float k_gc, k_gs, k_ge;
float boundaryOpacity(float opacity, float gradientMagnitude) {
  return opacity * (k_gc + k_gs * pow(gradientMagnitude, k_ge));
}

// Silhouette enhancement: o_s = o·(k_sc + k_ss·(1 − |∇f_n·V|)^k_se). `facing` = |n·v|.
uniform float k_sc, k_ss, k_se;
float silhouetteOpacity(float opacity, float facing) {
  return opacity * (k_sc + k_ss * pow(max(1.0 - facing, 0.0), k_se));
}

// Oriented fading, in HSV without leaving RGB: with f = |n·v|^k_fe (1 facing the viewer),
// saturation ×(1 − k_fs·f) and value ×(1 − k_fv·(1 − f)) keep the hue (c' = V − s·(V − c)
// scales S by s, c·w scales V by w); opacity ×(1 − k_fo·f). Neutral (all 0) leaves c and o
// exactly as they were.
uniform float k_fs, k_fv, k_fo, k_fe;
void orientedFading(inout vec3 color, inout float opacity, float facing) {
  float f = pow(facing, k_fe);
  float saturation = 1.0 - k_fs * f;
  float value = 1.0 - k_fv * (1.0 - f);
  float brightest = max(color.r, max(color.g, color.b));
  color = (color * saturation + vec3(brightest) * (1.0 - saturation)) * value;
  opacity *= 1.0 - k_fo * f;
}

// Sketch lines: regions facing the viewer transparent, silhouette regions in the sketch colour,
// opacity ×min(1, k_ls·|∇f|²·(1 − |n·v|)^k_le). Lines are drawn on surfaces, and a surface is
// where the gradient is strong (|∇f| normalized by the volume's largest, squared as boundary
// enhancement's Figure 3 does): without it the random normals of a CT's noisy homogeneous
// inside (|∇f| about 0.05 on the engine, 0.3 at its surfaces) and the nested shells of smooth
// data turn away from the viewer somewhere along every ray, and sketch alone drew a black blob.
uniform float k_ls, k_le;
uniform vec3 sketchColor;
void sketchLines(inout vec3 color, inout float opacity, float facing, float gradientMagnitude) {
  color = sketchColor;
  float surface = gradientMagnitude * gradientMagnitude;
  opacity *= min(1.0, k_ls * surface * pow(max(1.0 - facing, 0.0), k_le));
}

// Distance colour blending: c_d = (1 − k_ds·d^k_de)·c + k_ds·d^k_de·c_b, d the normalized depth
// (the fraction of the distance through the volume along the view), c_b the background.
uniform float k_ds, k_de;
uniform vec3 backgroundColor;
vec3 distanceBlend(vec3 color, float depth) {
  float w = k_ds * pow(depth, k_de);
  return color * (1.0 - w) + backgroundColor * w;
}

// Feature halos darken (the paper's Section 5.2: regions just outside features "darker and more
// opaque, obscuring background elements"): the sample's colour ×max(0, 1 − k_hd·h), and the
// opacity k_ho·h the halo adds is a black layer behind the sample's material in the same sample:
// c·o premultiplied over the opacity o + (1 − o)·k_ho·h. An opaque sample stays as it was (no
// halo on a feature itself), an empty one turns black at k_ho·h. Adding the opacity in the
// sample's own lit colour instead made halos a pale glow wherever h is small or the sample is
// lit: in the soft fringe of smooth data, over a white background.
uniform float k_hd, k_ho;
void featureHalo(inout vec3 color, inout float opacity, float h) {
  color *= max(1.0 - k_hd * h, 0.0);
  float halo = clamp(k_ho * h, 0.0, 1.0);
  if (halo <= 0.0) return;
  float material = clamp(opacity, 0.0, 1.0);
  float total = material + (1.0 - material) * halo;
  color *= material / total;
  opacity = total;
}

// Tone shading: I = k_ta·I_G + Σ_lights (I_t + k_td·I_o), I_t = t·c_w + (1 − t)·c_c with
// t = (1 + n·L)/2, c_w = (k_ty, k_ty, 0), c_c = (0, 0, k_tb), I_o = c_o·max(n·L, 0) (white
// lights). `lit` is I_G, `objectColor` c_o.
// The paper's sum overflows: at its Figure 7 values a white object facing the light gets
// 1 + 0.3 + 0.6 in red and green, and clamping turns every lit side white, warm tone and form
// lost. We keep the sum and scale it by toneScale = 1 / max(1, peak), the peak the largest
// channel the sum reaches for a white object over all normals with these parameters and lights
// (core/illustration.h toneShadingPeak, computed on the CPU): the result stays within [0, 1]
// for every colour, one factor for all samples and colours keeps the paper's proportions (warm
// against cool, lit colour against directed light), and a sum that fits is left as it is.
uniform float k_ta, k_td, k_ty, k_tb;
uniform float toneScale;
vec3 toneShade(vec3 lit, vec3 objectColor, vec3 n) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < LIGHT_COUNT; ++i) {
    float nl = dot(n, lightDirections[i]);
    float t = (1.0 + nl) * 0.5;
    sum += vec3(k_ty, k_ty, 0.0) * t + vec3(0.0, 0.0, k_tb) * (1.0 - t) +
           objectColor * (k_td * max(nl, 0.0));
  }
  return (lit * k_ta + sum) * toneScale;
}
