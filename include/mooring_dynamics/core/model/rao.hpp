// Motion response amplitude operators (RAOs) of a hull: the complex amplitude of each of its six
// rigid-body motions per metre of wave amplitude, tabulated in wave frequency and heading, as a
// diffraction code computes them (core/io/rao_io.hpp reads WAMIT `.4` files and a CSV form).
//
// Conventions (docs/problem_format.md "vessel.raos"):
//  * Modes 1-6: surge, sway, heave [m per m of wave amplitude] along the hull's body axes x
//    (forward), y (port), z (up) at its mean position (REP 103/105), and roll, pitch, yaw [rad per
//    m] about those axes (right-handed: positive pitch puts the bow down), of the reference point.
//  * Heading beta [deg]: the direction the waves travel toward, counterclockwise from the body +x
//    axis (0: following seas, waves travel from stern to bow; 180: head seas). WAMIT's BETA.
//  * Complex value X = |X| e^{i alpha} with the motion x(t) = Re{X A e^{i omega t}} for the wave
//    elevation eta(t) = Re{A e^{i omega t}} at the reference point's mean position: alpha is the
//    phase LEAD of the motion over the elevation there (WAMIT's convention).
// Interpolation: bilinear in omega and beta on the real and imaginary parts; headings wrap at
// 360 deg. Outside the tabulated frequencies: an error (RaoExtend::None), zero, or the end value
// held (the file's choice). A heading in a gap wider than kMaxHeadingGapDeg between tabulated
// headings is an error rather than a guess; a port-starboard symmetric hull can be given on 0-180
// deg only (RaoSymmetry::PortStarboard: beta' = 360 - beta with sway, roll and yaw negated).
#pragma once

#include <array>
#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace mooring_dynamics {
namespace core {

enum class RaoExtend { None, Zero, Hold };
enum class RaoSymmetry { None, PortStarboard };

class RaoTable {
 public:
  static constexpr int kDofs = 6;
  /// Widest gap between neighbouring tabulated headings (wrapping at 360 deg) that a heading of
  /// the sea may fall in: motion RAOs change by much more than interpolation error over wider ones.
  static constexpr double kMaxHeadingGapDeg = 90.0;

  RaoTable() = default;
  /// omega [rad/s] strictly increasing (>= 1 value), headings [deg] in [0, 360) strictly increasing
  /// (>= 1 value); values[dof][ih * omega.size() + iw]. Throws std::invalid_argument when the
  /// sizes or orderings are wrong (the message names the frequency or heading).
  RaoTable(std::vector<double> omega, std::vector<double> headings_deg,
           std::array<std::vector<std::complex<double>>, kDofs> values);

  const std::vector<double>& omega() const { return omega_; }
  const std::vector<double>& headings() const { return headings_; }
  std::complex<double> value(int dof, std::size_t i_heading, std::size_t i_omega) const {
    return values_[dof][i_heading * omega_.size() + i_omega];
  }

  RaoExtend extend = RaoExtend::None;
  RaoSymmetry symmetry = RaoSymmetry::None;

  /// Empty when omega [rad/s] and heading beta [deg, any real] can be interpolated, else a message
  /// naming the value and the table's range or gap.
  std::string check(double omega, double heading_deg) const;
  /// The six complex RAOs at (omega, beta). Throws std::invalid_argument with check()'s message.
  std::array<std::complex<double>, kDofs> at(double omega, double heading_deg) const;

 private:
  /// The bracketing tabulated headings of beta (after symmetry): indices, weight of the second,
  /// whether the values are mirrored, and the gap [deg]. False when beta lies in no gap (empty table).
  struct HeadingBracket {
    std::size_t a = 0, b = 0;
    double w = 0.0;
    bool mirrored = false;
    double gap = 0.0;
  };
  HeadingBracket bracketHeading(double heading_deg) const;
  std::vector<double> omega_;
  std::vector<double> headings_;
  std::array<std::vector<std::complex<double>>, kDofs> values_;
};

/// Where a vessel's RAOs come from and how to read them (problem file `vessel.raos`).
struct RaoSource {
  enum class Format { Wamit, Csv };
  std::string file;                 ///< path, resolved against the problem file's folder
  Format format = Format::Wamit;    ///< WAMIT `.4` (from the extension `.4`) or CSV
  double ulen = 0.0;                ///< WAMIT: the length scale ULEN [m] of the run (rotations are given as xi L / A); > 0
  bool phase_lag = false;           ///< phases are lags (the conjugate of this file's convention)
  bool rotations_in_deg = false;    ///< CSV: rotations in deg per m (else rad per m)
  Eigen::Vector3d reference_point = Eigen::Vector3d::Zero();  ///< body frame [m]: the RAOs' origin
  RaoExtend extend = RaoExtend::None;
  RaoSymmetry symmetry = RaoSymmetry::None;
};

/// Name of mode 1-6 ("surge", ..., "yaw"), for messages.
const char* raoDofName(int dof);

}  // namespace core
}  // namespace mooring_dynamics
