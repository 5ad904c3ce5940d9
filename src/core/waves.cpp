// Placeholder until the wave module lands: validation only.
#include "mooring_dynamics/core/waves.hpp"

namespace mooring_dynamics {
namespace core {

std::string WaveSpec::validate() const { return {}; }

}  // namespace core
}  // namespace mooring_dynamics
