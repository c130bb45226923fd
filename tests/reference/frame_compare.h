#pragma once
// Comparing frames of any technique by what it returns (states, depth, shade, tone, colour).
#include <glm/glm.hpp>

#include "core/frame.h"
#include "core/options.h"
#include "core/volume.h"
#include "slicing/renderer.h"
#include "slicing/technique_table.h"

namespace vsil::test {

// Pixels where any buffer the frames hold differs (NaN equals NaN; every byte and float exact).
int differingPixels(const FrameBuffers& a, const FrameBuffers& b);

// The largest difference of any channel between two colour images of the same size.
double maxChannelDifference(const cv::Mat4f& a, const cv::Mat4f& b);
// The same at pixel (x, y) alone (row y, column x).
double maxChannelDifference(const cv::Mat4f& a, const cv::Mat4f& b, int y, int x);

// Pixels that show something: a state other than Empty, or a colour with alpha > 0.
int shownPixels(const FrameBuffers& frame);

// Options that make `technique` show the iso-surface at `iso` where it has an iso value; none
// otherwise (its defaults).
OptionValues isoOptions(const TechniqueInfo& technique, double iso);

// The object's straight colours: FrameBuffers::tone at Filled pixels (the tone fill), or the
// colour divided by alpha where alpha > 0.5 (colour techniques); NaN elsewhere.
cv::Mat3f objectColours(const FrameBuffers& frame);

// What tone shading made of a sphere seen head-on (orthographic, the object a disc): each
// object pixel's normal n estimated from its place on the disc (centre the mean of the object
// pixels, radius from their count), and its straight colour (objectColours).
struct ToneSides {
  int object = 0;
  int lit = 0, litWarm = 0;      // n·L > 0.25, and of those R > B
  int unlit = 0, unlitCool = 0;  // n·L < −0.25, and of those B > R
  int atWhite = 0;               // a channel at 255 in 8 bits (>= 254.5/255)
  float brightest = 0;           // the largest channel of any object pixel
};
// `light`: the unit direction towards the light in eye space (x right, y up, z to the viewer).
ToneSides toneSides(const cv::Mat3f& objectColours, glm::dvec3 light);

// An ivory sphere tone-shaded: `settings` show `volume` (gen:sphere) head-on, orthographic, in
// ivory (illustrate's tone effect, or a state technique's --fill tone). The paper's sum over
// ivory exceeds 1 where the sphere faces the light (1 + 0.3 + 0.6 at its Figure 7 values):
// scaled by its peak, the lit side stays warm, not white, and the far side cool, every pixel of
// each (light straight above), and the highlight still reaches nearly white (the default light).
void expectIvoryToneWarmWhereLitCoolWhereNotAndNotClipped(const Volume& volume,
                                                          RenderSettings settings);

}  // namespace vsil::test
