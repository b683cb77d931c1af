#pragma once
/// \file tool_resampling.h
/// What pcl_sparse_resample and pcl_sparse_decode share: resampling a model in a local frame when it lies
/// far from the origin (map coordinates), and writing the cloud back in the model's frame.

#include "tool_support.h"

#include <pcl_sparse/io/cloud_io.h>
#include <pcl_sparse/model/sparse_surface_model.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <string>

namespace pcl_sparse
{
  namespace tools
  {
    /// A resampled cloud in a local frame and that frame's origin in the model's frame. PointT, here and
    /// below: pcl::PointNormal, pcl::PointXYZRGBNormal or pcl::PointXYZINormal (resampledPointType).
    template <typename PointT = pcl::PointNormal>
    struct LocalCloud
    {
      pcl::PointCloud<PointT> cloud;
      Eigen::Vector3d origin = Eigen::Vector3d::Zero ();  ///< 0 unless the model lies far from the origin
    };

    /// Resamples \a model with \a resampling (its density, options, threads and progress already set). A
    /// model far from the origin for its size (localFrameOrigin of its seeds is not 0: map coordinates) is
    /// resampled moved to that origin, so that float coordinates keep the cloud's resolution.
    template <typename PointT>
    LocalCloud<PointT>
    resampleInLocalFrame (SparseSurfaceResampling<PointT>& resampling, const SparseSurfaceModel::ConstPtr& model);

    /// As above, in the local frame of \a origin (a tiled model's: the same for the whole model and any
    /// region of it, so a region's points are exactly the whole model's there).
    template <typename PointT>
    LocalCloud<PointT>
    resampleInLocalFrame (SparseSurfaceResampling<PointT>& resampling, const SparseSurfaceModel::ConstPtr& model,
                          const Eigen::Vector3d& origin);

    /// Writes \a local to \a path (.pcd / .ply) in the model's frame: float x y z where floats keep the
    /// cloud's resolution (the origin is 0, or every coordinate is within 16 extents of 0), else double
    /// x y z = origin + point (map coordinates; PCL's loader cannot read those into PointXYZ).
    template <typename PointT>
    void
    saveLocalCloud (const std::string& path, const LocalCloud<PointT>& local, bool binary);

    /// The -stream option of the resampling tools (auto, on or off; auto when absent): true to write
    /// the cloud with streamResampledCloud. auto streams whenever the output can be streamed (binary .pcd,
    /// .ply) and no -png needs the whole cloud; on throws where it cannot.
    /// \throws Error naming the option for another value, or on with an output that cannot be streamed
    bool
    chooseStreaming (const CommandLine& args, const std::string& output, bool binary, bool png);

    /// The help line of the -max-slope DEG option of the resampling tools.
    HelpLine
    maxSlopeHelpLine ();

    /// The help line of the -clearance C option of the resampling tools.
    HelpLine
    clearanceHelpLine ();

    /// The ownership options of the resampling tools, set on \a options when given:
    /// - -max-slope DEG: a patch samples only where its code is within DEG degrees of its frame normal
    ///   (PatchOwnershipOptions::max_slope_angle; 90: no bound);
    /// - -clearance C: places within C x the smaller patch radius under the surface of a patch facing away (and within
    ///   the larger of C and opposite_outside_clearance over it) are left unsampled
    ///   (PatchOwnershipOptions::opposite_clearance; 0: none).
    /// \throws Error naming the option for a slope outside (0, 90] or a negative clearance
    void
    readOwnershipOptions (const CommandLine& args, SparseSurfaceResamplingOptions& options);

    /// The -block N option of the resampling tools: N points per streamed block (default 2^21), and 64 N
    /// bytes of candidates kept from the weight pass (ResamplingStreamOptions); a streamed run takes
    /// about 200 N bytes besides the model. Sets them on \a resampling.
    /// \throws Error naming the option for a value out of [4096, 2^26]
    void
    setStreamBlock (const CommandLine& args, SparseSurfaceResamplingBase& resampling);

    /// What streamResampledCloud did.
    struct StreamedCloud
    {
      std::size_t points = 0;
      double resample_seconds = 0.0;  ///< the passes, writing included (the writes overlap them)
      double save_seconds = 0.0;      ///< the wait for the last writes, and the rename
      bool bounds_pass = false;       ///< map coordinates: a first pass found the cloud's bounds
    };

    /// As resampleInLocalFrame then saveLocalCloud, the same bytes, with memory bounded by the stream's
    /// block size instead of the point count (SparseSurfaceResampling::compute with a callback,
    /// PointNormalStreamWriter; PointNormalStreamWriter::supports (path, binary) must hold). A model in
    /// map coordinates is resampled twice: the first pass finds the bounds that decide between float and
    /// double x y z, as saveLocalCloud does from the whole cloud. \a frame_origin (optional) gives the local
    /// frame, as the second resampleInLocalFrame (a tiled model's).
    template <typename PointT>
    StreamedCloud
    streamResampledCloud (SparseSurfaceResampling<PointT>& resampling, const SparseSurfaceModel::ConstPtr& model,
                          const std::string& path, bool binary, const Eigen::Vector3d* frame_origin = nullptr);

    /// The attribute a resampled cloud of a model with \a channels carries: colour where it codes r, g and b
    /// (pcl::PointXYZRGBNormal), else intensity where it codes intensity (pcl::PointXYZINormal), else none
    /// (pcl::PointNormal); none if \a wanted is false (the tools' -no-attributes).
    CloudExtraField
    resampledExtraField (const std::vector<AttributeChannelInfo>& channels, bool wanted = true);

    /// "rgb", "intensity" or "none": the field \a extra writes after x y z, as the tools' --json says it.
    const char*
    extraFieldName (CloudExtraField extra);

    /// The help line of the -no-attributes option of the resampling tools.
    HelpLine
    noAttributesHelpLine ();

    /// Calls \a run with a null pointer of the point type that carries \a extra:
    /// run (static_cast<pcl::PointXYZRGBNormal*> (nullptr)) for colour, and so on.
    template <typename Run>
    decltype (auto)
    withPointTypeOf (CloudExtraField extra, Run&& run)
    {
      switch (extra)
      {
        case CloudExtraField::Colour: return run (static_cast<pcl::PointXYZRGBNormal*> (nullptr));
        case CloudExtraField::Intensity: return run (static_cast<pcl::PointXYZINormal*> (nullptr));
        case CloudExtraField::None: break;
      }
      return run (static_cast<pcl::PointNormal*> (nullptr));
    }
  } // namespace tools
} // namespace pcl_sparse
