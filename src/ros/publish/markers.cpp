#include "mooring_dynamics/ros/publish/markers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace mooring_dynamics {
namespace ros_bridge {

namespace {

std_msgs::ColorRGBA rgba(double r, double g, double b, double a) {
  std_msgs::ColorRGBA c;
  c.r = static_cast<float>(r);
  c.g = static_cast<float>(g);
  c.b = static_cast<float>(b);
  c.a = static_cast<float>(a);
  return c;
}

visualization_msgs::Marker baseMarker(const CableState& state, const std::string& ns, int type) {
  visualization_msgs::Marker m;
  m.header = state.header;
  m.ns = ns;
  m.id = 0;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.frame_locked = false;
  return m;
}

geometry_msgs::Point point(double x, double y, double z) {
  geometry_msgs::Point p;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

}  // namespace

std::vector<BodyMark> bodyMarks(const core::Problem& problem) {
  std::vector<BodyMark> out;
  std::vector<int> count(problem.bodies.size(), 0), seen(problem.bodies.size(), 0);
  for (const auto& seg : problem.segments)
    for (const auto& bp : seg.bodies)
      if (bp.body < count.size()) ++count[bp.body];
  double s0 = 0.0;
  for (const auto& seg : problem.segments) {
    for (const auto& bp : seg.bodies) {
      if (bp.body >= problem.bodies.size()) continue;
      const core::Body& b = problem.bodies[bp.body];
      BodyMark m;
      m.name = b.name.empty() ? "body" + std::to_string(bp.body) : b.name;
      if (count[bp.body] > 1) m.name += "_" + std::to_string(seen[bp.body]++);
      m.s = s0 + bp.at;
      m.diameter = b.diameter;
      m.buoyant = b.wet_weight < 0.0;
      out.push_back(m);
    }
    s0 += seg.length;
  }
  return out;
}

geometry_msgs::Point pointAtArclength(const CableState& state, double s) {
  const std::size_t n = std::min(state.s.size(), state.positions.size());
  if (n == 0) return geometry_msgs::Point();
  if (s <= state.s.front()) return state.positions.front();
  for (std::size_t i = 1; i < n; ++i) {
    if (s <= state.s[i]) {
      const double h = state.s[i] - state.s[i - 1];
      const double w = h > 0.0 ? (s - state.s[i - 1]) / h : 1.0;
      const auto& a = state.positions[i - 1];
      const auto& b = state.positions[i];
      return point(a.x + w * (b.x - a.x), a.y + w * (b.y - a.y), a.z + w * (b.z - a.z));
    }
  }
  return state.positions[n - 1];
}

MarkerOptions markerOptionsFor(const core::Problem& problem, double scale) {
  MarkerOptions o;
  o.scale = scale;
  o.bodies = bodyMarks(problem);
  if (problem.top.type == core::TopBoundary::Type::Buoy) {
    o.top_buoy = true;
    o.buoy_cylinder = problem.top.buoy.shape == core::SurfaceBuoy::Shape::Cylinder;
    o.buoy_diameter = problem.top.buoy.diameter;
    o.buoy_height = problem.top.buoy.totalHeight();
  }
  return o;
}

std_msgs::ColorRGBA tensionColor(double t, double tmin, double tmax) {
  const double span = tmax - tmin;
  double u = 0.5;
  if (std::isfinite(t) && std::isfinite(span) && span > 1e-12 * std::max(1.0, std::abs(tmax)))
    u = std::clamp((t - tmin) / span, 0.0, 1.0);
  // Hue 240 deg (blue) -> 0 deg (red) at full saturation and value.
  const double h = (1.0 - u) * 4.0;  // in sextants: 4 = blue, 2 = green, 0 = red
  const int i = static_cast<int>(std::floor(h));
  const double f = h - i;
  switch (i) {
    case 0: return rgba(1.0, f, 0.0, 1.0);        // red -> yellow
    case 1: return rgba(1.0 - f, 1.0, 0.0, 1.0);  // yellow -> green
    case 2: return rgba(0.0, 1.0, f, 1.0);        // green -> cyan
    case 3: return rgba(0.0, 1.0 - f, 1.0, 1.0);  // cyan -> blue
    default: return rgba(0.0, 0.0, 1.0, 1.0);     // blue
  }
}

visualization_msgs::MarkerArray makeMarkers(const CableState& state, const core::Environment& env,
                                            const MarkerOptions& options) {
  visualization_msgs::MarkerArray out;
  const std::size_t n = state.positions.size();
  if (n == 0) return out;

  // Extent of the drawing: the line and the water column below it. The seabed, sea surface and
  // colour bar sit at the line's mid y (0 for a 2-D line) and are as wide as its y extent plus a
  // margin.
  double xmin = state.positions[0].x, xmax = xmin, zmin = state.positions[0].z, zmax = zmin;
  double ymin = state.positions[0].y, ymax = ymin;
  for (const auto& p : state.positions) {
    xmin = std::min(xmin, p.x);
    xmax = std::max(xmax, p.x);
    ymin = std::min(ymin, p.y);
    ymax = std::max(ymax, p.y);
    zmin = std::min(zmin, p.z);
    zmax = std::max(zmax, p.z);
  }
  const double yc = 0.5 * (ymin + ymax);
  const double zbed_anchor = env.seabedElevation(state.positions[0].x, state.positions[0].y);
  zmin = std::min(zmin, zbed_anchor);
  zmax = std::max(zmax, 0.0);
  const double extent = std::max({xmax - xmin, ymax - ymin, zmax - zmin, 1.0});
  const double scale = std::isfinite(options.scale) && options.scale > 0.0 ? options.scale : 1.0;
  const double line_width = std::max(0.005 * extent, 0.01) * scale;
  const double sphere = std::max(0.02 * extent, 0.05) * scale;
  const double text = std::max(0.04 * extent, 0.1) * scale;

  // Cable, coloured by tension.
  double tmin = 0.0, tmax = 0.0;
  if (!state.tension.empty()) {
    tmin = *std::min_element(state.tension.begin(), state.tension.end());
    tmax = *std::max_element(state.tension.begin(), state.tension.end());
  }
  if (std::isfinite(options.tension_min) && std::isfinite(options.tension_max) &&
      options.tension_max > options.tension_min) {
    tmin = options.tension_min;
    tmax = options.tension_max;
  }
  {
    auto m = baseMarker(state, "cable", visualization_msgs::Marker::LINE_STRIP);
    m.scale.x = line_width;
    m.color = rgba(0.0, 1.0, 0.0, 1.0);
    m.points = state.positions;
    m.colors.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      m.colors.push_back(i < state.tension.size() ? tensionColor(state.tension[i], tmin, tmax)
                                                  : rgba(0.5, 0.5, 0.5, 1.0));
    if (n == 1) m.points.push_back(m.points[0]);  // a strip needs two points
    if (n == 1) m.colors.push_back(m.colors[0]);
    out.markers.push_back(m);
  }

  // Anchor and top.
  {
    auto m = baseMarker(state, "anchor", visualization_msgs::Marker::SPHERE);
    m.pose.position = state.positions.front();
    m.scale.x = m.scale.y = m.scale.z = 1.5 * sphere;
    m.color = rgba(0.25, 0.25, 0.25, 1.0);
    out.markers.push_back(m);
  }
  {
    auto m = baseMarker(state, "top", visualization_msgs::Marker::SPHERE);
    m.pose.position = state.positions.back();
    m.scale.x = m.scale.y = m.scale.z = 1.5 * sphere;
    m.color = rgba(1.0, 0.55, 0.0, 1.0);
    out.markers.push_back(m);
  }

  // Label: top tension in kN.
  {
    auto m = baseMarker(state, "label", visualization_msgs::Marker::TEXT_VIEW_FACING);
    m.pose.position = state.positions.back();
    constexpr double kLabelLineSpacing = 1.4;  // text heights between stacked labels
    m.pose.position.z += 1.5 * sphere + text * (1.0 + kLabelLineSpacing * std::max(options.label_row, 0));
    m.scale.z = text;
    m.color = rgba(1.0, 1.0, 1.0, 1.0);
    char buf[64];
    const double ttop = state.tension.empty() ? 0.0 : state.tension.back();
    std::snprintf(buf, sizeof buf, "T top = %.1f kN", ttop / 1000.0);
    m.text = options.label_name.empty() ? std::string(buf) : options.label_name + ": " + buf;
    if (!state.converged) m.text += " (not converged)";
    if (state.slack) m.text += " (slack)";
    out.markers.push_back(m);
  }

  // Seabed: a flat patch, or a strip following the bottom profile.
  const double margin = 0.15 * extent;
  const double x0 = xmin - margin, x1 = xmax + margin;
  const double half_width = 0.25 * extent + 0.5 * (ymax - ymin);
  const std_msgs::ColorRGBA sand = rgba(0.76, 0.64, 0.42, 0.8);
  if (env.seabed.profile.empty()) {
    auto m = baseMarker(state, "seabed", visualization_msgs::Marker::CUBE);
    const double thickness = 0.01 * extent;
    m.pose.position = point(0.5 * (x0 + x1), yc, env.seabedElevation(0.5 * (x0 + x1), yc) - 0.5 * thickness);
    m.scale.x = x1 - x0;
    m.scale.y = 2.0 * half_width;
    m.scale.z = thickness;
    m.color = sand;
    out.markers.push_back(m);
  } else {
    auto m = baseMarker(state, "seabed", visualization_msgs::Marker::TRIANGLE_LIST);
    m.scale.x = m.scale.y = m.scale.z = 1.0;
    m.color = sand;
    const int k = 100;
    for (int i = 0; i < k; ++i) {
      const double xa = x0 + (x1 - x0) * i / k, xb = x0 + (x1 - x0) * (i + 1) / k;
      const double za = env.seabedElevation(xa, yc), zb = env.seabedElevation(xb, yc);
      const geometry_msgs::Point a0 = point(xa, yc - half_width, za), a1 = point(xa, yc + half_width, za);
      const geometry_msgs::Point b0 = point(xb, yc - half_width, zb), b1 = point(xb, yc + half_width, zb);
      m.points.insert(m.points.end(), {a0, b0, b1, a0, b1, a1});
    }
    out.markers.push_back(m);
  }

  // Inline bodies and the surface buoy.
  for (std::size_t k = 0; k < options.bodies.size(); ++k) {
    const BodyMark& b = options.bodies[k];
    auto m = baseMarker(state, "bodies", visualization_msgs::Marker::SPHERE);
    m.id = static_cast<int>(k);
    m.pose.position = pointAtArclength(state, b.s);
    m.scale.x = m.scale.y = m.scale.z = std::max(b.diameter, sphere);
    m.color = b.buoyant ? rgba(1.0, 0.85, 0.0, 1.0) : rgba(0.3, 0.3, 0.3, 1.0);
    out.markers.push_back(m);
  }
  if (options.top_buoy) {
    auto m = baseMarker(state, "buoy", options.buoy_cylinder ? visualization_msgs::Marker::CYLINDER
                                                             : visualization_msgs::Marker::SPHERE);
    m.pose.position = state.positions.back();
    // The line hangs from the buoy's bottom: centre half a height above the top node.
    m.pose.position.z += 0.5 * options.buoy_height;
    m.scale.x = m.scale.y = std::max(options.buoy_diameter, sphere);
    m.scale.z = std::max(options.buoy_height, sphere);
    m.color = rgba(1.0, 0.45, 0.0, 0.9);
    out.markers.push_back(m);
  }

  // Colour scale: a bar of the tension colours beside the drawing, labelled at both ends.
  {
    const double bar_x = xmax + 0.08 * extent;
    const double bar_z0 = zmin + 0.25 * (zmax - zmin), bar_h = 0.5 * (zmax - zmin) + 1e-9;
    const int k = 20;
    auto m = baseMarker(state, "scale", visualization_msgs::Marker::CUBE_LIST);
    m.scale.x = m.scale.y = 0.03 * extent * scale;
    m.scale.z = bar_h / k;
    m.color = rgba(1.0, 1.0, 1.0, 1.0);
    for (int i = 0; i < k; ++i) {
      const double u = (i + 0.5) / k;
      m.points.push_back(point(bar_x, yc, bar_z0 + u * bar_h));
      m.colors.push_back(tensionColor(tmin + u * (tmax - tmin), tmin, tmax));
    }
    out.markers.push_back(m);
    const double values[2] = {tmin, tmax};
    for (int j = 0; j < 2; ++j) {
      auto t = baseMarker(state, "scale", visualization_msgs::Marker::TEXT_VIEW_FACING);
      t.id = 1 + j;
      t.pose.position = point(bar_x + 0.03 * extent * scale + 1.5 * text, yc, bar_z0 + j * bar_h);
      t.scale.z = 0.7 * text;
      t.color = rgba(1.0, 1.0, 1.0, 1.0);
      char buf[48];
      std::snprintf(buf, sizeof buf, "%.2f kN", values[j] / 1000.0);
      t.text = buf;
      out.markers.push_back(t);
    }
    auto title = baseMarker(state, "scale", visualization_msgs::Marker::TEXT_VIEW_FACING);
    title.id = 3;
    title.pose.position = point(bar_x, yc, bar_z0 + bar_h + 1.2 * text);
    title.scale.z = 0.7 * text;
    title.color = rgba(1.0, 1.0, 1.0, 1.0);
    title.text = "tension";
    out.markers.push_back(title);
  }

  if (options.sea_surface) {
    auto m = baseMarker(state, "sea_surface", visualization_msgs::Marker::CUBE);
    const double thickness = 0.002 * extent;
    m.pose.position = point(0.5 * (x0 + x1), yc, -0.5 * thickness);
    m.scale.x = x1 - x0;
    m.scale.y = 2.0 * half_width;
    m.scale.z = thickness;
    m.color = rgba(0.2, 0.5, 0.9, 0.2);
    out.markers.push_back(m);
  }
  return out;
}

}  // namespace ros_bridge
}  // namespace mooring_dynamics
