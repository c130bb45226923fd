// vsil sweep SWEEP.json: a parameter sweep, one render per task, spread over the ranks of an MPI
// world (mpirun -np N vsil sweep ..., srun -n N under Slurm; mpi/task_farm.h: dynamic
// scheduling) or run in this one process without a launcher. The results come together on rank
// 0 as one JSON and/or CSV, one row per task in task order; a task that fails says why in its
// row and the others complete (exit status 3 then, core/error.h PartialFailure).
//
// The sweep file (strictly checked; errors name the file and the key):
//   {"render": {"input": "gen:spheres:32", "size": "32x32", "technique": "silhouette"},
//    "axes":   {"view": ["0,10", "30,20"], "width": [1, 2, 4]},
//    "tasks":  [{"input": "other.nrrd"}],
//    "measure_widths": true}
// Keys are `vsil render`'s flags without "--" ("width-near" or "width_near"; "input" is INPUT);
// values are a string or number (the flag's value), true/false (a switch on or off) or an array
// (a flag taking several, given once per item). The tasks are the product of the axes over
// "render" (the last axis varies fastest), then each entry of "tasks" over "render". A key that
// is no render flag fails the sweep before any render; a value the render refuses fails its task.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>

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
#include "core/progress_line.h"
#include "core/version.h"
#include "job/render_job.h"
#include "mpi/mpi_world.h"
#include "mpi/task_farm.h"
#include "postfx/line_width.h"
#include "serve/render_command_line.h"
#include "slicing/technique_table.h"

namespace vsil::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

// More tasks than this is a mistake in the axes (rows are kept in memory on rank 0).
constexpr long long kMaxTasks = 100000;

struct SweepFlags {
  std::string file;
  std::string json, csv, outDir;
  bool stateImages = false, depthImages = false, quiet = false;
};

// One task: the render command line it runs and the values that make it differ from "render".
struct SweepTask {
  serve::RenderCommandLine line;
  Json swept = Json::object();
};

struct SweepPlan {
  std::vector<SweepTask> tasks;
  bool measureWidths = false;
};

// The flags a sweep may set: `vsil render`'s render flags, by name, and whether each is a switch.
const std::map<std::string, bool>& renderFlagSwitches() {
  static const std::map<std::string, bool> flags = [] {
    std::map<std::string, bool> found;
    CLI::App app;
    RenderFlags scratch;
    addRenderOptions(app, scratch);
    for (const CLI::Option* option : app.get_options()) {
      const std::string name = option->get_single_name();
      if (name != "help") found[name] = option->get_expected_min() == 0;
    }
    return found;
  }();
  return flags;
}

std::string flagName(std::string key) {
  for (char& c : key) c = c == '_' ? '-' : c;
  return key;
}

std::string valueText(const Json& value, const std::string& where) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number()) return value.dump();
  throwInputError(where, "must be a string or a number (got " + jsonSnippet(value) + ")");
}

// Sets `key` to `value` on `line` (replacing what it had): the structural checks only.
void setFlag(serve::RenderCommandLine& line, const std::string& key, const Json& value,
             const std::string& where) {
  const std::string name = flagName(key);
  if (name == "input") {
    line.input = valueText(value, where);
    return;
  }
  const auto known = renderFlagSwitches().find(name);
  if (known == renderFlagSwitches().end() || known->first == "input") {
    throwInputError(where, "no render flag --" + name + " (keys are vsil render's flags)");
  }
  std::erase_if(line.flags, [&](const serve::GivenFlag& flag) { return flag.name == name; });
  if (known->second) {
    if (!value.is_boolean()) throwInputError(where, "a switch takes true or false");
    if (value.get<bool>()) line.flags.push_back({name, {}});
    return;
  }
  serve::GivenFlag flag{name, {}};
  if (value.is_array()) {
    if (value.empty()) throwInputError(where, "is an empty array");
    for (std::size_t i = 0; i < value.size(); ++i) {
      flag.values.push_back(valueText(value[i], where + "[" + std::to_string(i) + "]"));
    }
  } else {
    flag.values.push_back(valueText(value, where));
  }
  line.flags.push_back(flag);
}

// "width_near" and "width-near" name one flag: two such keys in one object would set it twice
// (the row's "swept" then reported a value that was not rendered).
void checkOneKeyPerFlag(const Json& object, const std::string& where) {
  std::map<std::string, std::string> keyOf;  // flag name -> the first key naming it
  for (const auto& [key, value] : object.items()) {
    const auto [it, added] = keyOf.emplace(flagName(key), key);
    if (!added) {
      throwInputError(where + ": " + key, "names the same flag as " + it->second + ": give one");
    }
  }
}

void checkFixedPerRank(const std::string& key, const std::string& where) {
  const std::string name = flagName(key);
  if (name == "gl" || name == "gl-device") {
    throwInputError(where, "--" + name +
                               " is the same for every task (one GL context per rank): "
                               "set it in \"render\"");
  }
}

SweepPlan readSweepPlan(const std::string& path) {
  const Json document = readOrderedJsonFile(path);
  if (!document.is_object()) throwInputError(path, "must be a JSON object");
  checkJsonKeys(nlohmann::json(document), {"render", "axes", "tasks", "measure_widths"}, path);
  SweepPlan plan;
  serve::RenderCommandLine base;
  base.input = kDefaultInput;
  if (document.contains("render")) {
    const Json& render = document["render"];
    if (!render.is_object()) throwInputError(path + ": render", "must be an object of flags");
    checkOneKeyPerFlag(render, path + ": render");
    for (const auto& [key, value] : render.items()) {
      setFlag(base, key, value, path + ": render: " + key);
    }
  }
  if (document.contains("measure_widths")) {
    if (!document["measure_widths"].is_boolean()) {
      throwInputError(path + ": measure_widths", "must be true or false");
    }
    plan.measureWidths = document["measure_widths"].get<bool>();
  }
  std::vector<std::pair<std::string, std::vector<Json>>> axes;
  long long product = 1;
  if (document.contains("axes")) {
    const Json& given = document["axes"];
    if (!given.is_object()) throwInputError(path + ": axes", "must be an object of arrays");
    checkOneKeyPerFlag(given, path + ": axes");
    for (const auto& [key, values] : given.items()) {
      const std::string where = path + ": axes: " + key;
      checkFixedPerRank(key, where);
      // A swept flag's value in "render" would never be used (every task takes the axis's).
      if (document.contains("render")) {
        for (const auto& [renderKey, renderValue] : document["render"].items()) {
          if (flagName(renderKey) == flagName(key)) {
            throwInputError(where, "is swept, and \"render\" sets it too (" + renderKey +
                                       "), which no task would use: give it in one place");
          }
        }
      }
      if (!values.is_array() || values.empty()) {
        throwInputError(where, "must be a non-empty array of values");
      }
      serve::RenderCommandLine probe = base;
      for (std::size_t i = 0; i < values.size(); ++i) {
        setFlag(probe, key, values[i], where + "[" + std::to_string(i) + "]");
      }
      product *= (long long)values.size();
      if (product > kMaxTasks) {
        throwInputError(path + ": axes", "more than " + std::to_string(kMaxTasks) + " tasks");
      }
      axes.emplace_back(key, std::vector<Json>(values.begin(), values.end()));
    }
  }
  std::vector<Json> extra;
  if (document.contains("tasks")) {
    const Json& given = document["tasks"];
    if (!given.is_array()) throwInputError(path + ": tasks", "must be an array of objects");
    for (std::size_t i = 0; i < given.size(); ++i) {
      const std::string where = path + ": tasks[" + std::to_string(i) + "]";
      if (!given[i].is_object()) throwInputError(where, "must be an object of flags");
      checkOneKeyPerFlag(given[i], where);
      serve::RenderCommandLine probe = base;
      for (const auto& [key, value] : given[i].items()) {
        checkFixedPerRank(key, where + ": " + key);
        setFlag(probe, key, value, where + ": " + key);
      }
      extra.push_back(given[i]);
    }
  }
  if (axes.empty() && extra.empty()) {
    plan.tasks.push_back({base, Json::object()});
    return plan;
  }
  if (!axes.empty()) {
    for (long long index = 0; index < product; ++index) {
      SweepTask task{base, Json::object()};
      long long rest = index;
      std::vector<std::size_t> picks(axes.size());
      for (std::size_t a = axes.size(); a-- > 0;) {
        picks[a] = std::size_t(rest % (long long)axes[a].second.size());
        rest /= (long long)axes[a].second.size();
      }
      for (std::size_t a = 0; a < axes.size(); ++a) {
        const Json& value = axes[a].second[picks[a]];
        setFlag(task.line, axes[a].first, value, path);
        task.swept[axes[a].first] = value;
      }
      plan.tasks.push_back(std::move(task));
    }
  }
  for (const Json& entry : extra) {
    SweepTask task{base, entry};
    for (const auto& [key, value] : entry.items()) setFlag(task.line, key, value, path);
    plan.tasks.push_back(std::move(task));
  }
  if ((long long)plan.tasks.size() > kMaxTasks) {
    throwInputError(path, "more than " + std::to_string(kMaxTasks) + " tasks");
  }
  return plan;
}

std::string taskFileName(int task, int tasks, const char* suffix) {
  const int digits = std::max(4, int(std::to_string(std::max(tasks - 1, 0)).size()));
  char name[64];
  std::snprintf(name, sizeof name, "task_%0*d%s.png", digits, task, suffix);
  return name;
}

// Runs tasks on this rank: one GL context and render job for all of them, the volume kept while
// consecutive tasks read the same one.
class TaskRunner {
 public:
  TaskRunner(const SweepPlan& plan, const SweepFlags& flags) : plan_(plan), flags_(flags) {}

  Json run(int index) {
    const auto start = Clock::now();
    const SweepTask& task = plan_.tasks[std::size_t(index)];
    Json row;
    row["task"] = index;
    row["status"] = "ok";
    row["error"] = nullptr;
    row["rank"] = mpi::rank();
    row["swept"] = task.swept;
    const int count = int(plan_.tasks.size());
    const fs::path outDir = flags_.outDir;
    const std::string image =
        outDir.empty() ? "" : (outDir / taskFileName(index, count, "")).string();
    row["command"] = task.line.shellText(image.empty() ? "task.png" : image);
    try {
      serve::CheckedRender checked = serve::checkRenderCommandLine(task.line);
      checked.request.settings.readDepth = flags_.depthImages;
      if (!job_) job_.emplace(toContextOptions(checked.flags.gl));
      const auto volumeKey = volumeFlags(task.line);
      StageClock clock;
      const bool reused = volumeKey == loadedKey_;
      if (!reused) {
        loadedKey_.clear();
        job_->load(task.line.input, RenderJob::loadOptionsFor(checked.request, checked.load));
        loadedKey_ = volumeKey;
      }
      const double loadMs = clock.lap().wallMs;
      RenderOutput output = job_->render(checked.request, checked.load.limits);
      const double renderMs = clock.lap().wallMs;
      Json outputs = Json::object();
      if (!outDir.empty()) {
        writePng(image, output.image);
        outputs["image"] = image;
        const TechniqueInfo& technique = findTechnique(checked.request.settings.technique);
        if (flags_.stateImages && technique.outputs.state) {
          const std::string file = (outDir / taskFileName(index, count, "_state")).string();
          writePng(file, stateImage(output.result.frame));
          outputs["state"] = file;
        }
        if (flags_.depthImages && technique.outputs.depth) {
          const std::string file = (outDir / taskFileName(index, count, "_depth")).string();
          writePng(file, depthImage(output.result.frame));
          outputs["depth"] = file;
        }
      }
      const double writeMs = clock.lap().wallMs;
      row["outputs"] = outputs;
      const nlohmann::json& meta = output.metadata;
      row["dataset"] = {{"name", meta["dataset"]["name"]}, {"dims", meta["dataset"]["dims"]}};
      row["slices"] = meta["slices"];
      row["pixels"] = meta["pixels"];
      if (plan_.measureWidths) row["widths"] = measureWidths(output, checked.request);
      row["warnings"] = output.warnings;
      row["volume_reused"] = reused;
      row["timings_ms"] = {{"load", loadMs},
                           {"render", meta["timings_ms"]["render"]},
                           {"postfx", meta["timings_ms"]["postfx"]},
                           {"render_job", renderMs},
                           {"write", writeMs},
                           {"total", millisecondsSince(start)}};
    } catch (const std::bad_alloc&) {
      fail(row, "out of memory", start);
    } catch (const std::exception& e) {
      fail(row, e.what(), start);
    }
    return row;
  }

 private:
  static void fail(Json& row, const std::string& error, Clock::time_point start) {
    row["status"] = "failed";
    row["error"] = error;
    row["timings_ms"] = {{"total", millisecondsSince(start)}};
  }

  // The input and the volume flags: what the loaded volume depends on.
  static std::string volumeFlags(const serve::RenderCommandLine& line) {
    static const std::set<std::string> volumeNames = [] {
      std::set<std::string> names;
      CLI::App app;
      VolumeOptions scratch;
      addVolumeOptions(app, scratch);
      for (const CLI::Option* option : app.get_options()) names.insert(option->get_single_name());
      return names;
    }();
    std::string key = line.input;
    for (const auto& flag : line.flags) {
      if (!volumeNames.count(flag.name)) continue;
      key += "\n--" + flag.name;
      for (const auto& value : flag.values) key += " " + value;
    }
    return key;
  }

  // The line widths of a line technique's illustration, measured on its lines' medial axes
  // (postfx/line_width.h, as `vsil measure-width`); null for a technique without lines or a
  // frame without any.
  static Json measureWidths(const RenderOutput& output, const RenderRequest& request) {
    if (!findTechnique(request.settings.technique).outputs.state) return nullptr;
    const cv::Mat1b mask = lineMaskFromImage(output.image, request.postfx.lineColor);
    std::vector<double> widths;
    for (const auto& sample :
         measureLineWidths(mask, "the rendered image", limits::defaultMemoryBytes())) {
      widths.push_back(sample.width);
    }
    if (widths.empty()) return nullptr;
    const WidthStatistics stats = summarizeWidths(widths);
    return {{"count", stats.count}, {"mean", stats.mean}, {"median", stats.median},
            {"p05", stats.p05},     {"p95", stats.p95},   {"min", stats.min},
            {"max", stats.max}};
  }

  const SweepPlan& plan_;
  const SweepFlags& flags_;
  std::optional<RenderJob> job_;
  std::string loadedKey_;
};

// Rows as CSV: one column per leaf of the rows' JSON (dotted names: swept.view, pixels.filled),
// in the order they first appear; arrays as JSON text; RFC 4180 quoting.
std::string csvText(const std::vector<Json>& rows) {
  std::vector<std::string> columns;
  std::set<std::string> seen;
  std::vector<std::map<std::string, std::string>> cells(rows.size());
  const std::function<void(const Json&, const std::string&, std::size_t)> flatten =
      [&](const Json& value, const std::string& name, std::size_t row) {
        if (value.is_object() && !value.empty()) {
          for (const auto& [key, item] : value.items()) {
            flatten(item, name.empty() ? key : name + "." + key, row);
          }
          return;
        }
        if (value.is_object()) return;
        if (seen.insert(name).second) columns.push_back(name);
        cells[row][name] = value.is_null()     ? ""
                           : value.is_string() ? value.get<std::string>()
                                               : jsonText(value);
      };
  for (std::size_t i = 0; i < rows.size(); ++i) flatten(rows[i], "", i);
  const auto quoted = [](const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
    std::string out = "\"";
    for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
  };
  std::string text;
  for (std::size_t c = 0; c < columns.size(); ++c) text += (c ? "," : "") + quoted(columns[c]);
  text += "\n";
  for (const auto& row : cells) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const auto cell = row.find(columns[c]);
      text += (c ? "," : "") + (cell == row.end() ? std::string() : quoted(cell->second));
    }
    text += "\n";
  }
  return text;
}

void run(const SweepFlags& flags) {
  const auto start = Clock::now();
  // Under a launcher every rank must share the work; a build without MPI cannot, and N copies
  // each running the whole sweep would only overwrite each other's files.
  if (mpi::launched()) mpi::require("vsil sweep under an MPI launcher");
  // The flags', the plan's and the outputs' checks: under mpirun the ranks agree, and a refusal
  // is said once by rank 0 (mpi::refuseAlike).
  SweepPlan plan;
  OutputBatch batch;
  std::optional<std::string> refusal;
  try {
    if (flags.json.empty() && flags.csv.empty()) {
      throw InputError("sweep: nothing to write (give --json FILE and/or --csv FILE)");
    }
    // The sweep file is read first: an output naming it is refused before any task runs.
    plan = readSweepPlan(flags.file);
    batch.claim("--json", flags.json);
    batch.claim("--csv", flags.csv);
    if (!flags.outDir.empty()) {
      refuseOutputFolder("--out-dir " + flags.outDir, flags.outDir);
      // A folder of images where a result file goes.
      batch.claim("--out-dir", flags.outDir, OutputKind::Folder);
    }
  } catch (const InputError& e) {
    refusal = e.what();
  }
  mpi::refuseAlike(refusal);
  if (validateOnly()) return;
  if (!flags.outDir.empty() && mpi::rank() == 0) {
    std::error_code error;
    // Its parent is there (refuseOutputFolder); "out/." is made as out.
    fs::create_directory(fs::path(flags.outDir).lexically_normal(), error);
    if (error) {
      refusal = "--out-dir " + flags.outDir + ": cannot create the folder: " + error.message();
    }
  }
  mpi::refuseAlike(refusal);

  const int count = int(plan.tasks.size());
  TaskRunner runner(plan, flags);
  std::vector<Json> rows(static_cast<std::size_t>(count));
  int done = 0, failed = 0, milestone = 0;
  vsil::ProgressLine progress(std::cerr, isatty(STDERR_FILENO) == 1);
  const auto loopStart = Clock::now();
  mpi::runTaskFarm(
      count, [&](int task) { return jsonText(runner.run(task)); },
      [&](int task, const std::string& result, int) {
        rows[std::size_t(task)] = Json::parse(result);
        ++done;
        if (rows[std::size_t(task)]["status"] != "ok") ++failed;
        if (flags.quiet) return;
        const std::string text =
            progressText(done, count, millisecondsSince(loopStart) / 1000.0, {"task", "tasks/s"},
                         failed ? std::to_string(failed) + " failed," : std::string());
        if (done * 10 / count > milestone) {
          milestone = done * 10 / count;
          progress.milestone(text);
        } else {
          progress.update(text);
        }
      });
  progress.finish();
  if (mpi::rank() != 0) return;

  const double seconds = millisecondsSince(start) / 1000.0;
  Json document;
  document["vsil_version"] = kVsilVersion;
  document["sweep"] = flags.file;
  document["ranks"] = mpi::size();
  document["tasks"] = count;
  document["ok"] = count - failed;
  document["failed"] = failed;
  document["seconds"] = seconds;
  document["rows"] = rows;
  if (!flags.json.empty()) batch.add(flags.json, jsonText(document, 1) + "\n");
  if (!flags.csv.empty()) batch.add(flags.csv, csvText(rows));
  batch.commit();
  std::ostream& report = reportStream({flags.json, flags.csv});
  for (const auto& path : {flags.json, flags.csv}) {
    if (!path.empty() && !namesStandardOutput(path)) report << path << "\n";
  }
  char summary[160];
  std::snprintf(summary, sizeof summary, "%d tasks on %d rank%s in %.2f s: %d ok, %d failed", count,
                mpi::size(), mpi::size() == 1 ? "" : "s", seconds, count - failed, failed);
  report << summary << "\n";
  if (failed) {
    int listed = 0;
    for (const Json& row : rows) {
      if (row["status"] == "ok") continue;
      if (++listed > 5) break;
      std::cerr << "vsil: task " << row["task"].get<int>() << ": "
                << row["error"].get<std::string>() << "\n";
    }
    throw PartialFailure(std::to_string(failed) + " of " + std::to_string(count) +
                         " tasks failed (their rows say why; the others completed)");
  }
}

const CommandRegistration registerSweepCommand(25, [](CLI::App& app) {
  auto flags = std::make_shared<SweepFlags>();
  CLI::App* command = app.add_subcommand(
      "sweep",
      "Render a parameter sweep (SWEEP.json: base flags, axes, tasks), one render per task, over "
      "the MPI ranks when launched by mpirun/srun; rows gathered into JSON/CSV");
  command->add_option("sweep", flags->file, "The sweep file (JSON)")->required();
  nonEmpty(command->add_option("--json", flags->json, "JSON of the sweep and one row per task"));
  nonEmpty(command->add_option("--csv", flags->csv, "CSV: one row per task, one column per field"));
  nonEmpty(command->add_option("--out-dir", flags->outDir,
                               "Folder for each task's image task_0000.png ... (none without it)"));
  command->add_flag("--state-images", flags->stateImages,
                    "Also task_NNNN_state.png (line techniques; with --out-dir)");
  command->add_flag("--depth-images", flags->depthImages,
                    "Also task_NNNN_depth.png (with --out-dir)");
  command->add_flag("--quiet", flags->quiet, "No progress line on stderr");
  command->callback([flags] { run(*flags); });
});

}  // namespace
}  // namespace vsil::cli
