#pragma once
// --up: which world axis shows upward and which faces the viewer at --view 0,0 (camera.h
// Upright). By default ("auto") a volume whose file places it in a patient's anatomical frame
// (NIfTI qform/sform, DICOM patient position, NRRD's anatomical `space`) stands superior up,
// seen from anterior, as medical viewers show it; any other volume, +y up and +z front.
// The world is the volume's index space scaled by the spacing (camera.h): the file's placement
// only chooses the axes, it is not applied, so data whose index axes are a mirror image of the
// patient (e.g. NIfTI's radiological LAS) still render mirrored.
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/volume.h"

namespace vsil {

// What --up resolved to for a volume, for the camera and --meta-out.
struct ResolvedUpright {
  Upright upright;
  std::string up;     // the axes as text: "+z"
  std::string front;  // "-y"
  std::string from;   // why: "--up +z", "the default (no anatomical placement)", "sform (RAS)"
};

// `flag`: "auto", or an axis "+x", "-x", "+y", "-y", "+z", "-z" ("x" for "+x"). An axis alone
// fixes its front as the orbit's defaults do: ±y up faces ±z, ±z up faces ∓y, ±x up faces +z.
// Throws InputError "--up: ..." for other text.
ResolvedUpright resolveUpright(const std::string& flag, const std::vector<Orientation>& placements);

// The anatomical letters of three index axes whose directions are `directions`' columns, in a
// space whose +x, +y, +z are `spaceAxes` ("RAS": Right, Anterior, Superior; "LPS"): "LPS" for
// axes towards Left, Posterior, Superior. Chosen together, as nifticlib chooses NIfTI's: the
// assignment of axes to directions whose cosines sum highest, so that an oblique placement (rows
// 45° between x and y) still names each direction once. (nibabel's aff2axcodes takes each axis
// alone and may differ near 45°.)
std::string anatomicalAxes(const glm::dmat3& directions, std::string_view spaceAxes);

}  // namespace vsil
