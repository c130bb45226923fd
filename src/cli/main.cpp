// vsil: volume silhouette illustration. Only this file turns errors into exit statuses:
// 2 for bad input (files, flags, parameters), 1 for internal failures and for what this machine
// lacks (UnavailableError: no usable OpenGL back end, a driver without a needed feature) and for
// results that failed their own check (CheckFailed: `vsil bench`'s self-checks), 3 when
// a command finished with some of its parts failed (PartialFailure: tasks of `vsil sweep`).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <optional>
#include <string>

#include "cli/cli_parse.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "mpi/mpi_world.h"

namespace {

constexpr int kPartialFailureStatus = 3;

// vsil's command line. Options may read the files they name while they are parsed (--rules,
// --tf, --style), which under mpirun can fail on some ranks only (a node without the file):
// once every option is parsed and before the command runs, the ranks meet (mpi::refuseAlike),
// and a rank whose options were refused meets them from run()'s handler with its message, so
// that the refusal is one line from rank 0 and no rank waits for another.
class VsilApp : public CLI::App {
 public:
  using CLI::App::App;
  bool optionsParsed() const { return optionsParsed_; }

 private:
  void pre_callback() override {
    optionsParsed_ = true;
    vsil::mpi::refuseAlike(std::nullopt);
  }
  bool optionsParsed_ = false;
};

// An error every rank has: said once, by rank 0; every rank ends without aborting the others.
int everyRankFails(const vsil::mpi::EveryRankError& e) {
  if (vsil::mpi::rank() == 0) std::cerr << "vsil: " << e.what() << "\n";
  vsil::mpi::failAlike();
  return e.status();
}

int run(int argc, char** argv) {
  // Ctrl-C, SIGTERM, SIGHUP: remove the temporary file of an output being written, then die
  // of the signal as usual (core/atomic_file.h). Targets are only ever replaced by rename().
  vsil::installOutputCleanupOnSignals();
  // No output of the command may replace a file it reads (core/atomic_file.h).
  vsil::recordInputFiles();
  VsilApp app{"vsil: silhouettes and illustrations of volume data, rendered offscreen"};
  vsil::cli::setUpApp(app);
  try {
    vsil::mpi::requireSameCommand(argc, argv);
    app.parse(argc, argv);
    // A report lost on its way out (a full disk behind `> info.json`, a closed stdout) is no
    // success: stdout's buffer is flushed here, where a failure can still be told.
    std::cout.flush();
    if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
      const int error = errno;
      throw vsil::InputError(std::string("standard output: cannot write") +
                             (error ? std::string(": ") + std::strerror(error) : ""));
    }
    return 0;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // The arguments alone decide it, and every rank has the same (requireSameCommand): under
    // mpirun rank 0 says it once and no rank aborts the others.
    if (vsil::mpi::rank() == 0) {
      std::cerr << "vsil: " << vsil::cli::parseErrorText(e) << " (see vsil --help)\n";
    }
    vsil::mpi::failAlike();
    return 2;
  } catch (const vsil::InputError& e) {
    if (!app.optionsParsed() && vsil::mpi::size() > 1) {
      try {
        vsil::mpi::refuseAlike(std::string(e.what()));  // throws on every rank
      } catch (const vsil::mpi::EveryRankError& every) {
        return everyRankFails(every);
      }
    }
    std::cerr << vsil::mpi::errorPrefix() << e.what() << "\n";
    return 2;
  } catch (const vsil::mpi::EveryRankError& e) {
    return everyRankFails(e);
  } catch (const vsil::PartialFailure& e) {
    std::cerr << vsil::mpi::errorPrefix() << e.what() << "\n";
    return kPartialFailureStatus;
  } catch (const vsil::UnavailableError& e) {
    std::cerr << vsil::mpi::errorPrefix() << e.what() << "\n";
    return 1;
  } catch (const vsil::CheckFailed& e) {
    std::cerr << vsil::mpi::errorPrefix() << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << vsil::mpi::errorPrefix()
              << "internal error: out of memory (lower --size or --max-memory)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << vsil::mpi::errorPrefix() << "internal error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Under mpirun or srun every rank runs this same command (src/mpi/mpi_world.h).
  vsil::mpi::initIfLaunched(&argc, &argv);
  const int status = run(argc, argv);
  // A partial failure is an orderly end: every rank finished and the results were gathered, so
  // MPI finalizes as usual (no MPI_Abort) and the status still says that some parts failed.
  if (status == kPartialFailureStatus) {
    vsil::mpi::finish(0);
    return status;
  }
  return vsil::mpi::finish(status);
}
