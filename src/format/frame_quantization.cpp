#include <pcl_sparse/format/frame_quantization.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace pcl_sparse
{
  QuantisedFrame
  quantiseFrame (const Eigen::Matrix3d& frame, double step)
  {
    QuantisedFrame code;
    Eigen::Matrix3d rotation = frame;
    code.reflected = frame.determinant () < 0.0;
    if (code.reflected)
      rotation.col (1) = -rotation.col (1);
    Eigen::Quaterniond quaternion (rotation);
    quaternion.normalize ();
    const double c[4] = {quaternion.w (), quaternion.x (), quaternion.y (), quaternion.z ()};
    int largest = 0;
    for (int i = 1; i < 4; ++i)
      if (std::abs (c[i]) > std::abs (c[largest]))
        largest = i;
    const double sign = c[largest] < 0.0 ? -1.0 : 1.0;  // q and -q are the same rotation
    code.largest = largest;
    for (int i = 0, k = 0; i < 4; ++i)
      if (i != largest)
        code.q[k++] = std::llround (sign * c[i] / step);
    return code;
  }

  bool
  dequantiseFrame (const QuantisedFrame& code, double step, Eigen::Matrix3d& frame)
  {
    if (code.largest < 0 || code.largest > 3)
      return false;
    double c[4];
    double sum = 0.0;
    for (int i = 0, k = 0; i < 4; ++i)
    {
      if (i == code.largest)
        continue;
      c[i] = static_cast<double> (code.q[k++]) * step;
      sum += c[i] * c[i];
    }
    // Rounding can push a legitimate code slightly past 1; a corrupt one is far past it.
    if (!std::isfinite (sum) || sum > 1.0 + 4.0 * step)
      return false;
    c[code.largest] = std::sqrt (std::max (0.0, 1.0 - sum));
    Eigen::Quaterniond quaternion (c[0], c[1], c[2], c[3]);
    quaternion.normalize ();
    frame = quaternion.toRotationMatrix ();
    if (code.reflected)
      frame.col (1) = -frame.col (1);
    return true;
  }

  double
  frameStep (double budget, double radius, double reach)
  {
    return budget / (1.1 * 2.0 * std::sqrt (3.0) * radius * reach);
  }

  double
  coefficientStep (double budget, double radius, std::size_t num_atoms)
  {
    return 2.0 * budget / (radius * static_cast<double> (std::max<std::size_t> (num_atoms, 1)));
  }
} // namespace pcl_sparse
