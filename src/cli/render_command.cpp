// vsil render: one frame of a technique to PNG, with optional state, depth and metadata files.
// The work is the library's render job (job/render_job.h); this file reads flags and writes files.
#include <iostream>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/cli_parse.h"
#include "cli/cli_progress.h"
#include "cli/cli_render_options.h"
#include "cli/cli_report.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/image_file.h"
#include "core/json_input.h"
#include "job/render_job.h"
#include "mpi/mpi_world.h"
#ifdef VSIL_HAVE_MPI
#include "mpi/rank_report.h"
#include "mpi/slab_render.h"
#endif
#include "slicing/technique_table.h"

namespace vsil::cli {
namespace {

// The outputs only `render` writes; everything else is the shared render flags.
struct RenderOutputs {
  std::string out = "vsil.png";
  std::string stateOut, depthOut, metaOut;
};

// Outputs the technique cannot make, and two outputs naming one file, are refused before any
// work.
void checkOutputs(const RenderFlags& flags, const RenderOutputs& outputs, OutputBatch& batch) {
  noteInputFile(flags.input);  // an output naming the volume file is refused before any work
  batch.claim("--out", outputs.out);
  batch.claim("--state-out", outputs.stateOut);
  batch.claim("--depth-out", outputs.depthOut);
  batch.claim("--meta-out", outputs.metaOut);
  // After the claims, which say first that a name is a folder, an input or another output's.
  requirePngName("--out", outputs.out);
  requirePngName("--state-out", outputs.stateOut);
  requirePngName("--depth-out", outputs.depthOut);
  const TechniqueInfo& technique = findTechnique(flags.technique);
  if (!outputs.stateOut.empty() && !technique.outputs.state) {
    throw InputError("--state-out: technique '" + technique.name + "' makes no state image");
  }
  if (!outputs.depthOut.empty() && !technique.outputs.depth) {
    throw InputError("--depth-out: technique '" + technique.name + "' makes no depth image");
  }
}

// timings_ms and cpu_ms (--meta-out): the frame's stages (render_job.cpp) and the command's own.
void addTimings(nlohmann::json& meta,
                const std::vector<std::pair<const char*, StageTime>>& stages) {
  for (const auto& [name, time] : stages) {
    meta["timings_ms"][name] = time.wallMs;
    meta["cpu_ms"][name] = time.cpuMs;
  }
}

void run(const RenderFlags& flags, const RenderOutputs& outputs) {
  // Start-up: exec to here (loading the shared libraries, static initialisers, parsing flags).
  const StageTime startup{millisecondsSinceProcessStart().value_or(0.0), processCpuMilliseconds()};
  StageClock whole, clock;
  // Under a launcher a build without MPI would be N copies of the whole render racing for one
  // file: it says so instead (.ci/run checks the line).
  if (mpi::launched() && !mpi::built()) mpi::require("vsil render under an MPI launcher");
  // The flags' and outputs' checks. Under mpirun every rank runs them alike, but a folder or the
  // memory may differ between nodes: the ranks agree, and a refusal is said once by rank 0.
  LoadOptions loadOptions;
  RenderRequest request;
  OutputBatch batch;
  std::optional<std::string> refusal;
  try {
    loadOptions = toLoadOptions(flags.volume);
    request = toRenderRequest(flags);
    request.settings.readDepth = !outputs.depthOut.empty();
    RenderJob::checkRequest(request, loadOptions.limits);
    checkOutputs(flags, outputs, batch);
  } catch (const InputError& e) {
    refusal = e.what();
  }
  mpi::refuseAlike(refusal);
  // Under mpirun with several ranks: a combine rule the slab renderer does not run, and options
  // that need the volume in one texture (a slab is not), refuse alike on every rank before
  // reading anything.
  const TechniqueInfo& technique = findTechnique(request.settings.technique);
  try {
    requireSplittable(technique, mpi::size());
    // The silhouette's slabs reduce their pairs on rank 0, which holds no volume to tone-shade
    // the hits with; relayed techniques tone-shade slab by slab (technique.h relayScreenPass).
    if (mpi::size() > 1 && technique.composition == Composition::PairReduce &&
        request.postfx.fill == FillMode::Tone) {
      throw UnavailableError(
          "--fill tone: not across MPI ranks yet (it shades every hit with the volume there); "
          "run one rank");
    }
  } catch (const UnavailableError& e) {
    throw mpi::EveryRankError(e.what());
  }
  if (mpi::size() > 1 && technique.needsOneTextureInSlab(request.settings.options)) {
    throw mpi::EveryRankError("--technique " + request.settings.technique +
                              ": these options need the volume in one texture, which a slab "
                              "rendered across MPI ranks is not; run one rank");
  }
  const gl::ContextOptions glOptions = toContextOptions(flags.gl);
  if (validateOnly()) return;

  // The whole render's memory is checked from the file's header, before any payload is read.
  LoadOptions load = RenderJob::loadOptionsFor(request, loadOptions);
  ProgressLine progress("reading " + flags.input);
  load.progress = progress.callback();
  clock.restart();
  RenderJob job(glOptions);
  const StageTime context = clock.lap();
  // Under mpirun with several ranks, each reads and renders only its slab (mpi/slab_render.h).
  const bool acrossRanks = mpi::size() > 1;
  nlohmann::json mpiMeta;
#ifdef VSIL_HAVE_MPI
  std::optional<mpi::SlabRead> slab;
  mpi::RankNumbers rankNumbers;
  if (acrossRanks) {
    // Ghost layers wide enough for what the technique reads beside its samples in this view.
    const Volume probe = mpi::probeSlab(flags.input, load);
    const glm::ivec3 dims = mpi::fileDims(probe);
    const int ghost = techniqueGhostVoxels(
        technique, request.settings.options,
        makeView(cameraFor(request, probe), dims, probe.spacing, request.settings.size), dims);
    slab.emplace(mpi::readSlab(flags.input, load, load.limits.maxTextureBytes, ghost));
    mpiMeta["ranks"] = mpi::size();
    mpiMeta["slabs"] = slab->slabs;
    mpiMeta["ghost_voxels"] = slab->part.ghostVoxels();
    mpiMeta["compose"] = compositionName(findTechnique(request.settings.technique).composition);
    rankNumbers.heldBytes =
        double(slab->volume.sampleBytes()) + double(mpi::heldTextureBytes(slab->part));
  }
#endif
  Volume loaded;
  if (!acrossRanks) loaded = loadVolume(flags.input, load);
  printVolumeWarnings(loaded);
#ifdef VSIL_HAVE_MPI
  // The file's warnings, said once: rank 0's slab is read from the file every rank reads.
  if (acrossRanks && mpi::rank() == 0) printVolumeWarnings(slab->volume);
#endif
  const StageTime read = clock.lap();
  progress.step("uploading the volume");
#ifdef VSIL_HAVE_MPI
  const Volume& volume =
      acrossRanks ? job.setSlab(std::move(slab->volume), slab->part, flags.input)
                  : job.setVolume(std::move(loaded), flags.input, load.limits.maxTextureBytes);
#else
  const Volume& volume = job.setVolume(std::move(loaded), flags.input, load.limits.maxTextureBytes);
#endif
  progress.finish();
  const StageTime upload = clock.lap();
  StageClock frameClock;
  RenderOutput output = job.render(request, loadOptions.limits);
  [[maybe_unused]] const StageTime frame = frameClock.elapsed();  // for the mpi metadata
  // Every rank has the same warnings (from the flags): said once.
  if (mpi::rank() == 0) printWarnings(output.warnings);
#ifdef VSIL_HAVE_MPI
  if (acrossRanks) {
    // Collectives on every rank; only rank 0 writes.
    rankNumbers.frameMs = frame.wallMs - output.result.timings.programs.wallMs;
    rankNumbers.frameCpuMs = frame.cpuMs - output.result.timings.programs.cpuMs;
    rankNumbers.renderMs = output.result.timings.render.wallMs;
    rankNumbers.reduceMs = output.result.timings.combine.wallMs;
    rankNumbers.peakResidentBytes = mpi::peakResidentBytes();
    rankNumbers.checkedBytes = double(
        RenderJob::memoryBytes(request, volume.dims, volume.type(), load.limits.maxTextureBytes));
    nlohmann::json perRank = mpi::gatherRankNumbers(rankNumbers);
    if (mpi::rank() != 0) return;
    mpiMeta["per_rank"] = std::move(perRank);
  }
#endif
  clock.restart();

  // Every output is complete before any replaces its target (core/atomic_file.h OutputBatch).
  batch.add(outputs.out, encodePng(outputs.out, output.image));
  if (!outputs.stateOut.empty()) {
    batch.add(outputs.stateOut, encodePng(outputs.stateOut, stateImage(output.result.frame)));
  }
  if (!outputs.depthOut.empty()) {
    batch.add(outputs.depthOut, encodePng(outputs.depthOut, depthImage(output.result.frame)));
  }
  const StageTime write = clock.lap();  // encoding: the files are renamed at the end
  if (!outputs.metaOut.empty()) {
    nlohmann::json& meta = output.metadata;
    meta["parameters"]["out"] = outputs.out;
    if (auto howRead = describeRead<nlohmann::json>(volume); !howRead.is_null()) {
      meta["dataset"]["read"] = howRead;
    }
    if (auto file = describeFile<nlohmann::json>(volume); !file.is_null()) {
      meta["dataset"]["file"] = file;
    }
    StageTime total = startup;
    total += whole.elapsed();
    addTimings(meta, {{"startup", startup},
                      {"context", context},
                      {"read", read},
                      {"upload", upload},
                      {"write", write},
                      {"total", total}});
    if (acrossRanks) meta["mpi"] = mpiMeta;
    batch.add(outputs.metaOut, jsonText(meta, 2) + "\n");
  }
  batch.commit();
  if (!namesStandardOutput(outputs.out)) {
    reportStream({outputs.stateOut, outputs.depthOut, outputs.metaOut}) << outputs.out << "\n";
  }
}

const CommandRegistration registerRenderCommand(10, [](CLI::App& app) {
  auto flags = std::make_shared<RenderFlags>();
  auto outputs = std::make_shared<RenderOutputs>();
  CLI::App* command = app.add_subcommand("render", "Render one frame of a technique to PNG");
  addRenderOptions(*command, *flags);
  nonEmpty(command->add_option("--out", outputs->out, "Output PNG")->capture_default_str());
  nonEmpty(command->add_option(
      "--state-out", outputs->stateOut,
      "8-bit PNG of pixel states: 0 Empty, 85 Filled, 170 Contour, 255 Silhouette"));
  nonEmpty(command->add_option("--depth-out", outputs->depthOut,
                               "16-bit PNG of normalized depth d: 1 + round(d*65534), 0 where none "
                               "(for line techniques: the line pixels)"));
  nonEmpty(
      command->add_option("--meta-out", outputs->metaOut, "JSON with parameters, camera, timings"));
  command->callback([flags, outputs] { run(*flags, *outputs); });
});

}  // namespace
}  // namespace vsil::cli
