#pragma once
/// \file surface_renderer.h
/// A headless software renderer: triangles rasterised and points drawn as square-ish splats into one
/// depth buffer, Lambert-shaded from their normals with a light fixed to the camera. No X server, no GPU.
///
/// Deterministic: projection and shading run in parallel, one result per vertex or point; the raster is
/// written by one thread in input order, the nearer fragment winning and the earlier one on ties, so the
/// image depends only on the input, not on the thread count (a 1-million-point cloud takes ~0.1 s).

#include <pcl_sparse/common/color_map.h>
#include <pcl_sparse/mesh/triangle_mesh.h>
#include <pcl_sparse/render/render_camera.h>
#include <pcl_sparse/render/rgb_image.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace pcl_sparse
{
  /// Options of SurfaceRenderer.
  struct RenderOptions
  {
    int width = 800;                           ///< image width in pixels
    int height = 600;                          ///< image height in pixels
    RgbColor background = {255, 255, 255};     ///< colour where nothing is drawn
    RgbColor surface = {200, 200, 200};        ///< colour of vertices and points without their own colour
    /// Light direction in the camera frame (right, up, towards the viewer): from the upper left, in front.
    Eigen::Vector3d light = Eigen::Vector3d (-0.35, 0.45, 1.0).normalized ();
    double ambient = 0.25;                     ///< brightness of a surface facing away from the light
    /// Splat half-size in pixels (a point covers the disc of radius r + 0.5); 0: from the points' density
    /// on screen, so that neighbouring splats touch (1 .. 8).
    int splat_radius = 0;
    /// Blend vertex colours across triangles; false: each pixel takes its nearest corner's colour (crisp
    /// patch boundaries).
    bool interpolate_colors = true;
    int marker_radius = 3;                     ///< radius in pixels of marker dots
    RgbColor marker = {220, 20, 20};           ///< colour of marker dots
  };

  /// \brief Renders a triangle mesh, a point cloud and marker dots (any of them) into an RgbImage.
  ///
  /// The inputs are held by pointer: they must outlive compute (). Normals of points may be missing
  /// (empty vector) or zero: such points are drawn unshaded at 0.8 brightness.
  class SurfaceRenderer
  {
  public:
    /// Sets the options.
    /// \param[in] options  size, colours, light, splat size
    void setOptions (const RenderOptions& options) { options_ = options; }
    /// The options.
    const RenderOptions& getOptions () const { return options_; }

    /// Sets the camera (fitRenderCamera makes one).
    /// \param[in] camera  the camera
    void setCamera (const RenderCamera& camera) { camera_ = camera; }

    /// Sets the mesh to draw, flat-shaded by face normal (two-sided).
    /// \param[in] mesh    the mesh, or nullptr for none
    /// \param[in] colors  one colour per vertex, or empty for RenderOptions::surface
    void setInputMesh (const TriangleMesh* mesh, const std::vector<RgbColor>* colors = nullptr);

    /// Sets the points to draw as splats.
    /// \param[in] positions  the points (non-finite ones skipped), or nullptr for none
    /// \param[in] normals    one normal per point, or nullptr / empty for unshaded points
    /// \param[in] colors     one colour per point, or nullptr / empty for RenderOptions::surface
    void setInputPoints (const std::vector<Eigen::Vector3d>* positions, const std::vector<Eigen::Vector3d>* normals = nullptr,
                         const std::vector<RgbColor>* colors = nullptr);

    /// Sets marker dots, drawn on top where they are not hidden behind the surface.
    /// \param[in] markers  the marked positions, or nullptr for none
    void setMarkers (const std::vector<Eigen::Vector3d>* markers) { markers_ = markers; }

    /// Renders.
    /// \param[out] image  RenderOptions::width x height pixels
    /// \throws pcl_sparse::Error if the image size is not in 1 .. 16384 or a colour or normal vector has
    ///         the wrong length
    void compute (RgbImage& image);

    /// Pixels covered by the surface in the last compute (not background).
    std::size_t getCoveredPixels () const { return covered_; }
    /// Splat radius used by the last compute (pixels).
    int getSplatRadius () const { return splat_radius_used_; }

  private:
    void drawMesh (RgbImage& image, std::vector<float>& depth) const;
    void drawPoints (RgbImage& image, std::vector<float>& depth);
    void drawMarkers (RgbImage& image, const std::vector<float>& depth) const;

    RenderOptions options_;
    RenderCamera camera_;
    const TriangleMesh* mesh_ = nullptr;
    const std::vector<RgbColor>* mesh_colors_ = nullptr;
    const std::vector<Eigen::Vector3d>* points_ = nullptr;
    const std::vector<Eigen::Vector3d>* normals_ = nullptr;
    const std::vector<RgbColor>* point_colors_ = nullptr;
    const std::vector<Eigen::Vector3d>* markers_ = nullptr;
    std::size_t covered_ = 0;
    int splat_radius_used_ = 0;
  };

  /// Lambert shading of a surface normal with the camera-fixed light, two-sided (a normal facing away
  /// from the viewer is flipped first, so back faces of open surfaces are lit like front faces).
  /// \param[in] camera   the camera (its axes turn \a normal into the camera frame)
  /// \param[in] normal   the normal in the world (need not be unit); zero: 0.8
  /// \param[in] light    unit light direction in the camera frame
  /// \param[in] ambient  brightness of a surface facing away from the light
  /// \return brightness in [ambient, 1]
  double
  lambertShade (const RenderCamera& camera, const Eigen::Vector3d& normal, const Eigen::Vector3d& light, double ambient);
} // namespace pcl_sparse
