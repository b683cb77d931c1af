#include <pcl_sparse_ros/parameters.h>

#include <pcl_sparse/common/error.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <vector>

namespace pcl_sparse_ros
{
  namespace
  {
    /// The parameter's value if set; throws if it is set but not a number.
    bool
    readNumber (const ros::NodeHandle& nh, const std::string& name, double& value)
    {
      if (!nh.hasParam (name))
        return false;
      if (!nh.getParam (name, value))
        throw pcl_sparse::Error ("parameter ~" + name + " must be a number");
      return true;
    }

    /// A list of three numbers, or a string of three numbers ("1.5 0 2" or "[1.5, 0, 2]": what
    /// `_viewpoint:=...` on a command line gives, since roscpp keeps such values as strings).
    std::vector<double>
    readTriple (const ros::NodeHandle& nh, const std::string& name)
    {
      std::vector<double> xyz;
      std::string text;
      if (nh.getParam (name, text))
      {
        for (char& c : text)
          if (c == '[' || c == ']' || c == ',')
            c = ' ';
        std::istringstream in (text);
        double v = 0.0;
        while (in >> v)
          xyz.push_back (v);
        if (!in.eof ())
          xyz.clear ();
      }
      else if (!nh.getParam (name, xyz))
        xyz.clear ();
      if (xyz.size () != 3 || !Eigen::Vector3d (xyz[0], xyz[1], xyz[2]).allFinite ())
        throw pcl_sparse::Error ("parameter ~" + name + " must be three numbers [x, y, z]");
      // setViewPoint takes floats (as pcl::Feature's): 1e300 became infinite there and failed every cloud.
      for (double v : xyz)
        if (!(std::abs (v) <= static_cast<double> (std::numeric_limits<float>::max ())))
          throw pcl_sparse::Error ("parameter ~" + name + " must be three numbers a float holds (|x| <= 3.4e38)");
      return xyz;
    }

    /// Throws, naming ~\a name, what the resampling stage's own setter says of the value (\a set calls it on a
    /// stage made for the check): the same bounds at start-up as on every cloud.
    void
    requireResamplingAccepts (const std::string& name,
                              const std::function<void (pcl_sparse::SparseSurfaceResamplingBase&)>& set)
    {
      pcl_sparse::SparseSurfaceResampling<pcl::PointNormal> stage;
      try
      {
        set (stage);
      }
      catch (const pcl_sparse::Error& e)
      {
        throw pcl_sparse::Error ("parameter ~" + name + ": " + e.what ());
      }
    }

    void
    requirePositive (const std::string& name, double value)
    {
      if (!(std::isfinite (value) && value > 0.0))
        throw pcl_sparse::Error ("parameter ~" + name + " must be a finite number > 0");
    }
  } // namespace

  void
  PointBudget::apply (pcl_sparse::SparseSurfaceResamplingBase& resampling, std::size_t default_count) const
  {
    switch (kind)
    {
      case Kind::Default: resampling.setPointCount (std::max<std::size_t> (default_count, 1)); break;
      case Kind::Points: resampling.setPointCount (static_cast<std::size_t> (value)); break;
      case Kind::Density: resampling.setDensity (value); break;
      case Kind::Spacing: resampling.setSpacing (value); break;
    }
  }

  std::string
  PointBudget::describe () const
  {
    std::ostringstream text;
    switch (kind)
    {
      case Kind::Default: return "default";
      case Kind::Points: text << "points " << static_cast<std::size_t> (value); break;
      case Kind::Density: text << "density " << value; break;
      case Kind::Spacing: text << "spacing " << value; break;
    }
    return text.str ();
  }

  PointBudget
  readPointBudget (const ros::NodeHandle& private_nh)
  {
    PointBudget budget;
    int given = 0;
    double value = 0.0;
    if (readNumber (private_nh, "points", value))
    {
      if (!(value >= 1.0 && value <= static_cast<double> (pcl_sparse::SparseSurfaceResamplingBase::max_points) &&
            value == std::floor (value)))
        throw pcl_sparse::Error ("parameter ~points must be a whole number from 1 to 1e9");
      budget = {PointBudget::Kind::Points, value};
      ++given;
    }
    if (readNumber (private_nh, "density", value))
    {
      requireResamplingAccepts ("density", [value] (pcl_sparse::SparseSurfaceResamplingBase& r) { r.setDensity (value); });
      budget = {PointBudget::Kind::Density, value};
      ++given;
    }
    if (readNumber (private_nh, "spacing", value))
    {
      // 1e-200 was taken here, then every cloud failed naming a density: setSpacing refuses it.
      requireResamplingAccepts ("spacing", [value] (pcl_sparse::SparseSurfaceResamplingBase& r) { r.setSpacing (value); });
      budget = {PointBudget::Kind::Spacing, value};
      ++given;
    }
    if (given > 1)
      throw pcl_sparse::Error ("parameters ~points, ~density and ~spacing: give at most one");
    return budget;
  }

  void
  ResamplingSettings::apply (pcl_sparse::SparseSurfaceResamplingBase& resampling, std::size_t default_count) const
  {
    resampling.setOptions (options);
    budget.apply (resampling, default_count);
  }

  std::string
  ResamplingSettings::describe () const
  {
    std::ostringstream text;
    text << budget.describe () << ", max slope " << options.ownership.max_slope_angle << ", clearance "
         << options.ownership.opposite_clearance;
    return text.str ();
  }

  ResamplingSettings
  readResamplingSettings (const ros::NodeHandle& private_nh)
  {
    ResamplingSettings settings;
    settings.budget = readPointBudget (private_nh);
    double degrees = 0.0;
    if (readNumber (private_nh, "max_slope", degrees))
    {
      if (!(degrees > 0.0 && degrees <= 90.0))
        throw pcl_sparse::Error ("parameter ~max_slope must be an angle in degrees in (0, 90]");
      settings.options.ownership.max_slope_angle = degrees;
    }
    double clearance = 0.0;
    if (readNumber (private_nh, "clearance", clearance))
    {
      if (!(clearance >= 0.0) || !std::isfinite (clearance))
        throw pcl_sparse::Error ("parameter ~clearance must be a finite number >= 0 (patch radii)");
      settings.options.ownership.opposite_clearance = clearance;
    }
    return settings;
  }

  pcl_sparse::SparseSurfaceEncoderOptions
  presetOptions (const std::string& preset)
  {
    // The library's presets (encoderPresetOptions), with the node's own parameter name in the error.
    if (preset == "paper" || preset == "default")
      return pcl_sparse::encoderPresetOptions (pcl_sparse::encoderPresetFromName (preset));
    throw pcl_sparse::Error ("parameter ~preset must be \"paper\" or \"default\", not \"" + preset + "\"");
  }

  EncoderSettings
  readEncoderSettings (const ros::NodeHandle& private_nh)
  {
    EncoderSettings settings;
    settings.preset = readString (private_nh, "preset", "default");
    settings.options = presetOptions (settings.preset);
    double rho = 0.0;
    if (readNumber (private_nh, "rho", rho))
    {
      requirePositive ("rho", rho);
      settings.options.patches.rho = rho;
    }
    if (private_nh.hasParam ("viewpoint"))
    {
      const std::vector<double> xyz = readTriple (private_nh, "viewpoint");
      settings.has_viewpoint = true;
      settings.viewpoint = Eigen::Vector3d (xyz[0], xyz[1], xyz[2]);
    }
    if (readNumber (private_nh, "model_tolerance", settings.model_tolerance) &&
        !(settings.model_tolerance >= 0.0 && settings.model_tolerance < 1.0))
      throw pcl_sparse::Error ("parameter ~model_tolerance must be in [0, 1) (0 = lossless)");
    settings.threads = readThreads (private_nh);
    try
    {
      settings.options.validate ();
    }
    catch (const pcl_sparse::Error& e)
    {
      throw pcl_sparse::Error (std::string ("encoder options (~preset, ~rho): ") + e.what ());
    }
    return settings;
  }

  int
  readThreads (const ros::NodeHandle& private_nh)
  {
    double threads = 0.0;
    // roscpp's param () took "abc" as 0 and rounded 2.7 to 3 without a word.
    if (readNumber (private_nh, "threads", threads) && !(threads >= 0.0 && threads <= 1024.0 && threads == std::floor (threads)))
      throw pcl_sparse::Error ("parameter ~threads must be a whole number in [0, 1024] (0 = all cores)");
    return static_cast<int> (threads);
  }

  std::string
  readString (const ros::NodeHandle& private_nh, const std::string& name, const std::string& fallback)
  {
    std::string value = fallback;
    if (private_nh.hasParam (name) && !private_nh.getParam (name, value))
      throw pcl_sparse::Error ("parameter ~" + name + " must be a string");
    return value;
  }
} // namespace pcl_sparse_ros
