#pragma once
// The Ebert–Rheingans formulas (IEEE Vis 2000; ../shared/papers/README.md), one function each,
// written again for the CPU references that apply them, independently of
// slicing/shaders/illustration.glsl.
#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "core/illustration.h"

namespace vsil::reference {

// All vectors in one space (the caller's: world axes for illustrate, eye space for the tone
// fill): n the outward unit normal (0 where the gradient vanishes), the lights' directions
// towards the lights.
struct IllustrationFormulas {
  const Illustration& ill;
  std::vector<glm::vec3> lights;  // towards the lights, in the space of n
  glm::vec3 sketch, background;   // the sketch colour, distance blending's c_b

  float p(const char* name) const { return float(ill[name]); }

  // I_G: ambient plus diffuse from every light.
  glm::vec3 lit(glm::vec3 c, glm::vec3 n) const {
    float diffuse = 0;
    for (const glm::vec3& l : lights) diffuse += std::max(glm::dot(n, l), 0.0f);
    return c * (p("k_a") + p("k_d") * diffuse);
  }
  // o_g = o_v·(k_gc + k_gs·|∇f|^k_ge)
  float boundary(float o, float m) const {
    return o * (p("k_gc") + p("k_gs") * std::pow(m, p("k_ge")));
  }
  // o_s = o·(k_sc + k_ss·(1 − |∇f_n·V|)^k_se)
  float silhouette(float o, float facing) const {
    return o * (p("k_sc") + p("k_ss") * std::pow(std::max(1.0f - facing, 0.0f), p("k_se")));
  }
  // Oriented fading in HSV: saturation ×(1 − k_fs·f), value ×(1 − k_fv·(1 − f)), opacity
  // ×(1 − k_fo·f), f = |n·v|^k_fe. Done through HSV here (the shader stays in RGB).
  void fading(glm::vec3& c, float& o, float facing) const {
    const float f = std::pow(facing, p("k_fe"));
    const float value = std::max({c.r, c.g, c.b});
    const float lowest = std::min({c.r, c.g, c.b});
    const float saturation = value > 0 ? (value - lowest) / value : 0.0f;
    const float newSaturation = saturation * (1.0f - p("k_fs") * f);
    const float newValue = value * (1.0f - p("k_fv") * (1.0f - f));
    // Hue kept: each channel keeps its position between the lowest and the highest.
    glm::vec3 out(newValue);
    if (value > lowest) {
      const glm::vec3 position = (c - lowest) / (value - lowest);  // 0 at the lowest, 1 at V
      const float newLowest = newValue * (1.0f - newSaturation);
      out = newLowest + position * (newValue - newLowest);
    }
    c = out;
    o *= 1.0f - p("k_fo") * f;
  }
  // Sketch: colour the sketch colour, o ×min(1, k_ls·|∇f|²·(1 − |n·v|)^k_le).
  void sketchLines(glm::vec3& c, float& o, float facing, float m) const {
    c = sketch;
    o *= std::min(1.0f, p("k_ls") * m * m * std::pow(std::max(1.0f - facing, 0.0f), p("k_le")));
  }
  // Halo h: the colour ×max(0, 1 − k_hd·h), then a black layer of opacity k_ho·h behind the
  // material in the same sample: premultiplied c·o over the opacity o + (1 − o)·k_ho·h.
  void halo(glm::vec3& c, float& o, float h) const {
    c *= std::max(1.0f - p("k_hd") * h, 0.0f);
    const float added = std::clamp(p("k_ho") * h, 0.0f, 1.0f);
    if (added <= 0) return;
    const float material = std::clamp(o, 0.0f, 1.0f);
    const float total = material + (1.0f - material) * added;
    c *= material / total;
    o = total;
  }
  // c_d = (1 − k_ds·d^k_de)·c + k_ds·d^k_de·c_b
  glm::vec3 distance(glm::vec3 c, float d) const {
    const float w = p("k_ds") * std::pow(d, p("k_de"));
    return c * (1.0f - w) + background * w;
  }
  // I = (k_ta·I_G + Σ (t·(k_ty, k_ty, 0) + (1 − t)·(0, 0, k_tb) + k_td·c_o·max(n·L, 0)))·s,
  // t = (1 + n·L)/2, s = 1/max(1, the sum's largest channel for a white object over all n).
  glm::vec3 tone(glm::vec3 litColor, glm::vec3 object, glm::vec3 n) const {
    return toneSum(litColor, object, n) / std::max(1.0f, tonePeak());
  }
  glm::vec3 toneSum(glm::vec3 litColor, glm::vec3 object, glm::vec3 n) const {
    glm::vec3 sum(0.0f);
    for (const glm::vec3& l : lights) {
      const float nl = glm::dot(n, l);
      const float t = (1.0f + nl) * 0.5f;
      sum += glm::vec3(p("k_ty"), p("k_ty"), 0) * t + glm::vec3(0, 0, p("k_tb")) * (1 - t) +
             object * (p("k_td") * std::max(nl, 0.0f));
    }
    return litColor * p("k_ta") + sum;
  }
  // The white object's sum at every normal where it can peak, and its largest channel there.
  // Where n faces the lights of a set S and no other, each channel's sum is linear in n, so it
  // peaks along its own gradient there: for the warm channels
  // (k_ty/2)·ΣL + (k_ta·k_d + k_td)·Σ_S L, for the cool one −(k_tb/2)·ΣL + the same.
  float tonePeak() const {
    const glm::vec3 white(1.0f);
    glm::vec3 all(0.0f);
    for (const glm::vec3& l : lights) all += l;
    const float directed = p("k_ta") * p("k_d") + p("k_td");
    const glm::vec3 none = toneSum(lit(white, glm::vec3(0.0f)), white, glm::vec3(0.0f));
    float peak = std::max({none.r, none.g, none.b});  // the constant part, where all w vanish
    for (unsigned subset = 0; subset < (1u << lights.size()); ++subset) {
      glm::vec3 facing(0.0f);
      for (std::size_t i = 0; i < lights.size(); ++i) {
        if ((subset >> i) & 1u) facing += lights[i];
      }
      for (const float signedTone : {p("k_ty") / 2, -p("k_tb") / 2}) {
        const glm::vec3 w = signedTone * all + directed * facing;
        if (glm::dot(w, w) == 0.0f) continue;
        const glm::vec3 n = glm::normalize(w);
        const glm::vec3 c = toneSum(lit(white, n), white, n);
        peak = std::max({peak, c.r, c.g, c.b});
      }
    }
    return peak;
  }
};

}  // namespace vsil::reference
