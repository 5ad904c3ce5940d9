#include "mooring_dynamics/ros/nodes/params.hpp"

#include <cmath>
#include <stdexcept>

#include "mooring_dynamics/ros/publish/converter.hpp"

namespace mooring_dynamics {
namespace ros_bridge {

double doubleParam(const ros::NodeHandle& pnh, const std::string& name, double def,
                   const std::function<bool(double)>& ok, const std::string& constraint) {
  double v = def;
  if (pnh.hasParam(name) && !pnh.getParam(name, v))
    throw std::runtime_error("parameter " + pnh.resolveName(name) + ": must be a number");
  if (!(std::isfinite(v) && ok(v)))
    throw std::runtime_error("parameter " + pnh.resolveName(name) + " = " + formatNumber(v) + ": " + constraint);
  return v;
}

int intParam(const ros::NodeHandle& pnh, const std::string& name, int def, int min, const std::string& constraint) {
  int v = def;
  if (pnh.hasParam(name) && !pnh.getParam(name, v))
    throw std::runtime_error("parameter " + pnh.resolveName(name) + ": must be an integer (" + constraint + ")");
  if (v < min) throw std::runtime_error("parameter " + pnh.resolveName(name) + " = " + std::to_string(v) + ": " + constraint);
  return v;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
