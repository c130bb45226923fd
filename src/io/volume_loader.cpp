#include "io/volume_loader.h"

#include "core/error.h"
#include "generators/generators.h"

namespace vsil {

Volume loadVolume(const std::string& spec, const LoadOptions& options) {
  if (spec.starts_with("gen:")) return generateVolume(spec.substr(4), options.limits);
  throwInputError(spec, "volume files cannot be read yet; use gen:NAME[:N]");
}

}  // namespace vsil
