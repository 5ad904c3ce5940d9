// Reading node parameters with errors that name the parameter, its value and the constraint
// (shared by the lockstep and vessel nodes).
#pragma once

#include <functional>
#include <string>

#include <ros/ros.h>

namespace mooring_dynamics {
namespace ros_bridge {

/// A double parameter (default `def` when absent); throws std::runtime_error naming it when it is
/// not a number, not finite, or `ok(v)` is false (`constraint` says what it must be).
double doubleParam(const ros::NodeHandle& pnh, const std::string& name, double def,
                   const std::function<bool(double)>& ok, const std::string& constraint);

/// An integer parameter (default `def`); throws naming it when it is not an integer or below `min`.
int intParam(const ros::NodeHandle& pnh, const std::string& name, int def, int min, const std::string& constraint);

}  // namespace ros_bridge
}  // namespace mooring_dynamics
