#include <pcl_sparse_ros/cloud_resampler.h>
#include <pcl_sparse_ros/shutdown.h>

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <pcl_conversions/pcl_conversions.h>

#include <boost/make_shared.hpp>

#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <utility>

namespace pcl_sparse_ros
{
  namespace
  {
    using Clock = std::chrono::steady_clock;

    double
    secondsSince (Clock::time_point start)
    {
      return std::chrono::duration<double> (Clock::now () - start).count ();
    }

    /// Encodes the message as a cloud of PointInT: setInputCloud alone, organized or not, NaN kept
    /// (the encoder decides what to do with them, as PCL stages do).
    template <typename PointInT>
    pcl_sparse::SparseSurfaceModel::Ptr
    encodeAs (const sensor_msgs::PointCloud2& input, const EncoderSettings& settings, ResampleResult& result)
    {
      auto cloud = std::make_shared<pcl::PointCloud<PointInT>> ();
      pcl::fromROSMsg (input, *cloud);

      pcl_sparse::SparseSurfaceEncoder<PointInT> encoder;
      encoder.setOptions (settings.options);
      encoder.setNumberOfThreads (settings.threads);
      encoder.setProgressCallback (stopWhenShuttingDown);
      encoder.setInputCloud (cloud);
      if (settings.has_viewpoint)
        encoder.setViewPoint (static_cast<float> (settings.viewpoint.x ()), static_cast<float> (settings.viewpoint.y ()),
                              static_cast<float> (settings.viewpoint.z ()));
      auto model = std::make_shared<pcl_sparse::SparseSurfaceModel> ();
      encoder.compute (*model);
      result.input_points = encoder.getCleaningReport ().finitePoints ();
      result.kept_points = encoder.getCleaningReport ().kept;
      return model;
    }

    pcl_sparse::SparseSurfaceModel::Ptr
    encode (const sensor_msgs::PointCloud2& input, const EncoderSettings& settings, ResampleResult& result)
    {
      switch (result.layout.input)
      {
        case InputLayout::XYZ: return encodeAs<pcl::PointXYZ> (input, settings, result);
        case InputLayout::XYZI: return encodeAs<pcl::PointXYZI> (input, settings, result);
        case InputLayout::XYZRGB: return encodeAs<pcl::PointXYZRGB> (input, settings, result);
        case InputLayout::XYZRGBA: return encodeAs<pcl::PointXYZRGBA> (input, settings, result);
        case InputLayout::Normal: return encodeAs<pcl::PointNormal> (input, settings, result);
        case InputLayout::XYZRGBNormal: return encodeAs<pcl::PointXYZRGBNormal> (input, settings, result);
      }
      throw pcl_sparse::Error ("unknown input layout");
    }

    /// Resamples into PointOutT. Colour and intensity are whatever the resampling gives them (0 until
    /// the model codes attributes).
    template <typename PointOutT>
    void
    resampleAs (const pcl_sparse::SparseSurfaceModel::ConstPtr& model, const ResamplingSettings& settings,
                std::size_t default_count, int threads, sensor_msgs::PointCloud2& output)
    {
      pcl_sparse::SparseSurfaceResampling<PointOutT> resampling;
      resampling.setInputModel (model);
      settings.apply (resampling, default_count);
      resampling.setNumberOfThreads (threads);
      resampling.setProgressCallback (stopWhenShuttingDown);
      pcl::PointCloud<PointOutT> cloud;
      resampling.compute (cloud);
      pcl::toROSMsg (cloud, output);
    }

    void
    resample (const pcl_sparse::SparseSurfaceModel::ConstPtr& model, const ResamplingSettings& settings,
              std::size_t default_count, int threads, OutputLayout layout, sensor_msgs::PointCloud2& output)
    {
      switch (layout)
      {
        case OutputLayout::Normal: return resampleAs<pcl::PointNormal> (model, settings, default_count, threads, output);
        case OutputLayout::XYZRGBNormal:
          return resampleAs<pcl::PointXYZRGBNormal> (model, settings, default_count, threads, output);
        case OutputLayout::XYZINormal:
          return resampleAs<pcl::PointXYZINormal> (model, settings, default_count, threads, output);
      }
    }
  } // namespace

  ResampleResult
  resampleCloud (const sensor_msgs::PointCloud2& input, const EncoderSettings& settings,
                 const ResamplingSettings& resampling, bool want_cloud, bool want_model,
                 const std::function<void (const sensor_msgs::PointCloud2::ConstPtr&)>& on_cloud)
  {
    ResampleResult result;
    result.layout = cloudLayoutOf (input);
    Clock::time_point start = Clock::now ();
    const pcl_sparse::SparseSurfaceModel::ConstPtr model = encode (input, settings, result);
    result.patches = model->numPatches ();
    result.encode_seconds = secondsSince (start);
    if (want_cloud)
    {
      start = Clock::now ();
      result.cloud = boost::make_shared<sensor_msgs::PointCloud2> ();
      resample (model, resampling, result.kept_points, settings.threads, result.layout.output, *result.cloud);
      result.cloud->header = input.header;
      result.resample_seconds = secondsSince (start);
      if (on_cloud)
        on_cloud (result.cloud);
    }
    if (want_model)
    {
      start = Clock::now ();
      pcl_sparse::ModelWriteOptions write;
      write.tolerance = settings.model_tolerance;
      result.model = pcl_sparse::encodeModel (*model, write);
      result.model_seconds = secondsSince (start);
    }
    return result;
  }

  std_msgs::UInt8MultiArray
  toModelMessage (std::vector<std::uint8_t>&& bytes)
  {
    std_msgs::UInt8MultiArray message;
    message.layout.dim.resize (1);
    message.layout.dim[0].label = "psm";
    message.layout.dim[0].size = static_cast<std::uint32_t> (bytes.size ());
    message.layout.dim[0].stride = static_cast<std::uint32_t> (bytes.size ());
    message.data = std::move (bytes);
    return message;
  }

  CloudResampler::CloudResampler (const ros::NodeHandle& private_nh)
    : name_ (private_nh.getNamespace ())
  {
    ros::NodeHandle nh = private_nh;
    settings_ = readEncoderSettings (nh);
    resampling_ = readResamplingSettings (nh);
    // Latched, and a subscriber that comes gets the last input encoded for it (serveLastInput).
    const ros::SubscriberStatusCallback on_subscriber = [this] (const ros::SingleSubscriberPublisher&) { serveLastInput (); };
    cloud_pub_ = nh.advertise<sensor_msgs::PointCloud2> ("output", 1, on_subscriber, ros::SubscriberStatusCallback (),
                                                         ros::VoidConstPtr (), true);
    model_pub_ = nh.advertise<std_msgs::UInt8MultiArray> ("model", 1, on_subscriber, ros::SubscriberStatusCallback (),
                                                          ros::VoidConstPtr (), true);
    // Queue of one: a frame that arrives while the previous one is being encoded replaces the waiting one.
    sub_ = nh.subscribe ("input", 1, &CloudResampler::onCloud, this);
    ROS_INFO ("[%s] resampling %s -> %s (%s), model on %s; preset %s, rho %g, %s, model tolerance %g",
              name_.c_str (), sub_.getTopic ().c_str (), cloud_pub_.getTopic ().c_str (), resampling_.describe ().c_str (),
              model_pub_.getTopic ().c_str (), settings_.preset.c_str (), settings_.options.patches.rho,
              settings_.has_viewpoint ? "viewpoint given" : "no viewpoint", settings_.model_tolerance);
  }

  void
  CloudResampler::onCloud (const sensor_msgs::PointCloud2ConstPtr& input)
  {
    last_input_ = input;
    cloud_served_ = model_served_ = false;
    serveLastInput ();
  }

  void
  CloudResampler::serveLastInput ()
  {
    const bool want_cloud = !cloud_served_ && cloud_pub_.getNumSubscribers () > 0;
    const bool want_model = !model_served_ && model_pub_.getNumSubscribers () > 0;
    if (!last_input_ || (!want_cloud && !want_model))
      return;  // nobody listens: no work (as pcl_ros's lazy nodelets), the input kept for who comes
    const sensor_msgs::PointCloud2ConstPtr input = last_input_;
    cloud_served_ = cloud_served_ || want_cloud;  // an input that fails is not tried again
    model_served_ = model_served_ || want_model;
    ResampleResult result;
    bool cloud_published = false;
    // The cloud goes out as soon as it is made: the model's bytes (~0.03 s on a 640x480 frame) come after.
    const auto publish_cloud = [this, &cloud_published] (const sensor_msgs::PointCloud2::ConstPtr& cloud) {
      cloud_pub_.publish (cloud);
      cloud_published = true;
    };
    try
    {
      result = resampleCloud (*input, settings_, resampling_, want_cloud, want_model, publish_cloud);
    }
    catch (const std::exception& e)  // not only the library's errors: std::bad_alloc ended the node (and a manager)
    {
      if (ros::ok ())
        errorThrottled ("cannot encode the cloud (frame '" + input->header.frame_id + "', " + describeCloud (*input) +
                        "): " + e.what () +
                        (cloud_published ? "; only the resampled cloud published" : "; nothing published"));
      return;
    }
    ROS_DEBUG ("[%s] %s: %zu points (%zu kept) -> %zu patches in %.3f s, resampled in %.3f s, %zu model bytes in %.3f s",
               name_.c_str (), pointTypeName (result.layout.input), result.input_points, result.kept_points, result.patches,
               result.encode_seconds, result.resample_seconds, result.model.size (), result.model_seconds);
    if (want_model)
      model_pub_.publish (boost::make_shared<const std_msgs::UInt8MultiArray> (toModelMessage (std::move (result.model))));
  }

  void
  CloudResampler::errorThrottled (const std::string& message)
  {
    const ros::WallTime now = ros::WallTime::now ();
    if (!last_error_.isZero () && (now - last_error_).toSec () < 10.0)
    {
      ++suppressed_errors_;
      return;
    }
    if (suppressed_errors_ > 0)
      ROS_ERROR ("[%s] %s (and %zu more messages since the last report)", name_.c_str (), message.c_str (),
                 suppressed_errors_);
    else
      ROS_ERROR ("[%s] %s", name_.c_str (), message.c_str ());
    last_error_ = now;
    suppressed_errors_ = 0;
  }
} // namespace pcl_sparse_ros
