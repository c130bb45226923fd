#pragma once
// The table of techniques: each declares itself once — its name, a one-line summary, its
// options with defaults and ranges (core/options.h), what its frames return, and how to make
// it. The CLI's flags and help, the metadata, the benchmark, the names listed in errors and the
// Python keywords all read this table. A new technique is a folder under slicing/techniques/
// and one entry in technique_table.cpp.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/composition.h"
#include "core/options.h"

namespace vsil {

class Technique;
struct View;

// What a technique's frames hold (core/frame.h FrameBuffers).
struct FrameOutputs {
  bool state = false;  // pixel states (Nagy–Klein) and the shade of FILLED pixels
  bool color = false;  // premultiplied RGBA
  bool depth = false;  // normalized depth of what each pixel shows
};

struct TechniqueInfo {
  std::string name;     // --technique NAME
  std::string summary;  // one line: what it draws, after which paper
  std::vector<OptionSpec> options;
  FrameOutputs outputs;
  std::function<std::unique_ptr<Technique>()> create;  // needs a current GL context
  // Samples the volume's gradient texture (slicing/gradient_texture.h): the render's memory
  // bound counts it.
  bool usesGradients = false;
  // Checks what the option declarations cannot: text values the technique parses itself and
  // rules between options. Throws InputError naming the flag; runs before any GL work.
  std::function<void(const OptionValues& given)> checkValues;
  // Whether a frame with these options needs the volume in one texture (what cannot follow
  // bricks: the tiles march, illustrate's halo taps): the renderer then uploads it in one
  // texture when it fits (BrickLayout::Bricking::OneIfItFits), else the frame refuses. Unset:
  // never.
  std::function<bool(const OptionReader& options)> needsOneTexture;
  // Samples off the slice planes, up to a step in front (common.glsl BOX_ALIGNED_SAMPLING): the
  // slice pieces get a wider margin and overlap by it across brick borders (slicer.h
  // slicePieces), and the slice shader keeps only the samples its brick owns.
  bool samplesOffPlanes = false;
  // How the partial frames of slabs rendered by different processes combine (`mpirun -np N
  // vsil render`, core/composition.h, where each rule is proved against the sequential fold).
  // Set in the table (technique_table.cpp techniqueTable).
  Composition composition = Composition::None;
  // A slab's frame runs the fast pipeline whatever --pipeline says (optionsForSlab), not only
  // at the default: the silhouette (its tile march needs one texture and its paper pipeline's
  // screen passes would clear pixels another process owns) and illustrate (slabs relay the
  // slice passes' colour and marks).
  bool slabRunsFastPipeline = false;
  // How far, in voxels along z, what a frame with these options reads beside its samples
  // reaches beyond them, for the frame's view of a volume of `dims` voxels: a slab holds that
  // many voxels of ghost bricks beyond those it owns (slab.h techniqueGhostVoxels,
  // mpi/slab_render.h readSlab). Unset: 0 (it reads only its own samples, the bricks' overlap
  // covering the filter).
  std::function<int(const OptionReader& options, const View& view, glm::ivec3 dims)>
      slabGhostVoxels = nullptr;
  // Options given that change nothing in a frame with these options (a sketch colour with the
  // sketch effect off): one line each, "--flag: why; ignored", which the frame warns with, as
  // with the line flags of a technique that draws no lines. Unset: none.
  std::function<std::vector<std::string>(const OptionReader& options)> ignoredOptions = nullptr;

  const OptionSpec* option(const std::string& optionName) const;
  bool usesIso() const { return option("iso") != nullptr; }
  // Whether a frame with the `given` options needs the volume in one texture (needsOneTexture;
  // derived defaults do not matter to it).
  bool needsOneTextureWith(const OptionValues& given) const;
  // Whether a slab's frame (rendered across MPI ranks) with the `given` options needs the volume
  // in one texture, which a slab is not, so that it refuses: needsOneTextureWith the options the
  // slab's frame runs with (optionsForSlab). The CLI asks before reading, the renderer again per
  // frame.
  bool needsOneTextureInSlab(OptionValues given) const;
};

const std::vector<TechniqueInfo>& techniqueTable();
// Throws UnavailableError "--technique NAME: rendering across N MPI ranks is not available
// yet (...)" when `ranks` > 1 and the technique's combine rule is not wired into the slab
// renderer (slicing/slab.h): MaxReduce, PairReduce and Relay are, so every technique of the
// table renders across ranks; LocalMaxReduce (proven, unused) is not. A single rank renders as
// without MPI.
void requireSplittable(const TechniqueInfo& info, int ranks);
// The entry named `name`; InputError "--technique: unknown technique 'x' (known: ...)".
const TechniqueInfo& findTechnique(const std::string& name);
std::vector<std::string> techniqueNames();

// The iso-value option of the techniques that look for an iso-surface.
OptionSpec isoOption();

// How a frame walks the slices (--pipeline), for the techniques that offer a choice
// (silhouette, rightangle, illustrate); every choice gives the same pixels (illustrate's the
// same samples, composited in the same order: colours equal to float rounding, since a slice
// pass and a compute shader round differently):
//   fast:  a pass or two per slice, skipping empty space and pixels that can no longer change;
//   paper: the papers' passes per slice over every pixel of each slice polygon, no skipping;
//   tiles: one compute dispatch marching screen tiles through the slices (tile_march.h).
// Each technique's default is its fastest pipeline (measured in the README's benchmark section).
enum class SlicingPipeline { Fast, Paper, Tiles };
const char* pipelineName(SlicingPipeline pipeline);  // "fast", "paper", "tiles"
OptionSpec pipelineOption(SlicingPipeline defaultPipeline);
SlicingPipeline pipelineOf(const OptionReader& options);
// needsOneTexture of the techniques with a pipeline: the tiles march when asked for by name.
// A default tiles pipeline never needs one texture: over a volume in several bricks it gives way
// to fast (optionsForBricks), so neither the memory check nor the upload counts a second copy.
bool tilesNeedOneTexture(const OptionReader& options);
// The options a frame of `info` runs with when the volume is held in `bricks` textures: `given`,
// plus --pipeline fast where the technique's default pipeline is tiles, none was given, and the
// volume takes several bricks (the tiles march needs one texture; uploading the volume again
// would cost the time and memory the default is meant to save). The metadata then records fast.
OptionValues optionsForBricks(const TechniqueInfo& info, OptionValues given, std::size_t bricks);
// The options a slab's frame (one MPI rank's part, slab.h) runs with: `given`, plus --pipeline
// fast where the technique has a pipeline and none was given (a slab is never one texture, which
// the tiles march needs), or whatever was given where slabRunsFastPipeline. The renderer runs
// the frame with them and the metadata records them; a tiles pipeline asked for by name
// elsewhere is refused before reading (needsOneTextureInSlab).
OptionValues optionsForSlab(const TechniqueInfo& info, OptionValues given);

}  // namespace vsil
