// Colour and intensity (issue 12 point 7): coded per patch over the height's atoms, resampled into the
// output's rgb / intensity fields, taken from a PCL cloud's fields automatically; known colour fields.
#include <pcl_sparse/coding/patch_attribute_coder.h>
#include <pcl_sparse/common/error.h>
#include <pcl_sparse/encoder/sparse_surface_encoder.h>
#include <pcl_sparse/format/model_file.h>
#include <pcl_sparse/io/scan_conversion.h>
#include <pcl_sparse/mesh/mesh_primitives.h>
#include <pcl_sparse/model/attribute_gaps.h>
#include <pcl_sparse/resampling/sparse_surface_resampling.h>

#include <gtest/gtest.h>

#include "error_message.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

using namespace pcl_sparse;

namespace
{
  /// The known field: r = 128 + 100 x, g = 128 + 100 y, b = 50, intensity = 1000 z.
  Eigen::Vector4d
  field (const Eigen::Vector3d& p)
  {
    return Eigen::Vector4d (128.0 + 100.0 * p.x (), 128.0 + 100.0 * p.y (), 50.0, 1000.0 * p.z ());
  }

  VertexAttributes::Ptr
  fieldAttributes (const TriangleMesh& mesh)
  {
    auto attributes = std::make_shared<VertexAttributes> ();
    attributes->channels = {AttributeChannel::Red, AttributeChannel::Green, AttributeChannel::Blue,
                            AttributeChannel::Intensity};
    attributes->values.resize (static_cast<Eigen::Index> (mesh.vertices.size ()), 4);
    for (std::size_t v = 0; v < mesh.vertices.size (); ++v)
      attributes->values.row (static_cast<Eigen::Index> (v)) = field (mesh.vertices[v]).cast<float> ().transpose ();
    return attributes;
  }

  SparseSurfaceModel::Ptr
  encode (const TriangleMesh& mesh, const VertexAttributes::ConstPtr& attributes)
  {
    SparseSurfaceEncoder<pcl::PointXYZ> encoder;
    encoder.setInputMesh (std::make_shared<TriangleMesh> (mesh));
    encoder.setVertexAttributes (attributes);
    auto model = std::make_shared<SparseSurfaceModel> ();
    encoder.compute (*model);
    return model;
  }

  template <typename PointT>
  pcl::PointCloud<PointT>
  resample (const SparseSurfaceModel::ConstPtr& model, std::size_t count)
  {
    SparseSurfaceResampling<PointT> resampling;
    resampling.setInputModel (model);
    resampling.setPointCount (count);
    pcl::PointCloud<PointT> cloud;
    resampling.compute (cloud);
    return cloud;
  }

  /// Mean and largest |resampled - field| of r, g and intensity / 10 (grey levels) over \a cloud.
  struct FieldError
  {
    double mean = 0.0, max = 0.0, intensity_mean = 0.0;
  };

  FieldError
  colourError (const pcl::PointCloud<pcl::PointXYZRGBNormal>& rgb, const pcl::PointCloud<pcl::PointXYZINormal>& intensity)
  {
    FieldError e;
    for (std::size_t i = 0; i < rgb.size (); ++i)
    {
      const Eigen::Vector4d expected = field (rgb[i].getVector3fMap ().cast<double> ());
      const double dr = std::abs (rgb[i].r - expected[0]), dg = std::abs (rgb[i].g - expected[1]);
      e.mean += (dr + dg) / (2.0 * rgb.size ());
      e.max = std::max ({e.max, dr, dg});
      e.intensity_mean += std::abs (intensity[i].intensity - expected[3]) / intensity.size ();
    }
    return e;
  }

  /// \a mesh's vertices as a PCL cloud with intensity 1000 z.
  pcl::PointCloud<pcl::PointXYZI>::Ptr
  intensityCloud (const TriangleMesh& mesh)
  {
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZI>> ();
    for (const Eigen::Vector3d& v : mesh.vertices)
    {
      pcl::PointXYZI p;
      p.getVector3fMap () = v.cast<float> ();
      p.intensity = static_cast<float> (1000.0 * v.z ());
      cloud->push_back (p);
    }
    return cloud;
  }

  /// \a mesh's triangles as PCL polygons.
  std::shared_ptr<std::vector<pcl::Vertices>>
  cloudPolygons (const TriangleMesh& mesh)
  {
    auto polygons = std::make_shared<std::vector<pcl::Vertices>> ();
    for (const Eigen::Vector3i& t : mesh.triangles)
    {
      pcl::Vertices polygon;
      polygon.vertices = {t[0], t[1], t[2]};
      polygons->push_back (polygon);
    }
    return polygons;
  }

  /// The model without its attributes.
  SparseSurfaceModel
  geometryOf (SparseSurfaceModel model)
  {
    model.attribute_channels.clear ();
    for (PatchCode& patch : model.patches)
      patch.attributes.clear ();
    return model;
  }
} // namespace

TEST (Attributes, SphereColourFieldIsResampledWithinAFewGreyLevels)
{
  const TriangleMesh sphere = makeIcosphere (4);
  const auto model = encode (sphere, fieldAttributes (sphere));
  ASSERT_EQ (model->attribute_channels.size (), 4u);
  EXPECT_EQ (model->attribute_channels[0].upper, 255.0);
  EXPECT_NEAR (model->attribute_channels[3].lower, -1000.0, 1e-3);
  EXPECT_NEAR (model->attribute_channels[3].upper, 1000.0, 1e-3);
  for (const PatchCode& patch : model->patches)
    ASSERT_EQ (patch.attributes.size (), 4u);

  const auto rgb = resample<pcl::PointXYZRGBNormal> (model, 20000);
  const auto intensity = resample<pcl::PointXYZINormal> (model, 20000);
  ASSERT_EQ (rgb.size (), 20000u);
  const FieldError e = colourError (rgb, intensity);
  std::printf ("sphere: %zu patches, colour |error| mean %.3f max %.1f grey levels, intensity mean %.3f (of 2000)\n",
               model->numPatches (), e.mean, e.max, e.intensity_mean);
  EXPECT_LT (e.mean, 1.0);
  EXPECT_LT (e.max, 6.0);
  EXPECT_LT (e.intensity_mean, 5.0);
  for (const auto& point : rgb)
    ASSERT_EQ (point.b, 50);  // a constant channel is exact
}

TEST (Attributes, PlaneColourFieldAndConstantColour)
{
  const TriangleMesh plane = makePlaneGrid (40);
  auto attributes = fieldAttributes (plane);
  attributes->values.col (3).setConstant (7.5f);  // intensity constant too
  const auto model = encode (plane, attributes);
  const auto rgb = resample<pcl::PointXYZRGBNormal> (model, 10000);
  const auto intensity = resample<pcl::PointXYZINormal> (model, 10000);
  double worst = 0.0;
  for (std::size_t i = 0; i < rgb.size (); ++i)
  {
    const Eigen::Vector4d expected = field (rgb[i].getVector3fMap ().cast<double> ());
    // Footprints overshoot the open border a little, where the field is extrapolated: compare inside.
    if (std::max (std::abs (rgb[i].x), std::abs (rgb[i].y)) <= 1.0f)
      worst = std::max ({worst, std::abs (rgb[i].r - expected[0]), std::abs (rgb[i].g - expected[1])});
    ASSERT_EQ (rgb[i].b, 50);
    ASSERT_EQ (intensity[i].intensity, 7.5f);
  }
  EXPECT_LT (worst, 5.0);
}

TEST (Attributes, GeometryIsTheSameWithOrWithoutAttributes)
{
  const TriangleMesh sphere = makeIcosphere (3);
  const auto plain = encode (sphere, nullptr);
  const auto coloured = encode (sphere, fieldAttributes (sphere));
  EXPECT_FALSE (plain->hasAttributes ());
  EXPECT_EQ (encodeModel (*plain), encodeModel (geometryOf (*coloured)));

  // And resampling draws the same points: attributes only add fields.
  const auto a = resample<pcl::PointNormal> (plain, 3000);
  const auto b = resample<pcl::PointXYZRGBNormal> (coloured, 3000);
  ASSERT_EQ (a.size (), b.size ());
  for (std::size_t i = 0; i < a.size (); ++i)
    ASSERT_EQ (a[i].getVector3fMap (), b[i].getVector3fMap ());
  // A model without attributes leaves the colour fields at PCL's defaults.
  const auto grey = resample<pcl::PointXYZRGBNormal> (plain, 100);
  EXPECT_EQ (grey[0].r, 0);
  EXPECT_EQ (grey[0].a, 255);
}

TEST (Attributes, CloudWithColourGivesTheColoursAutomatically)
{
  const TriangleMesh sphere = makeIcosphere (3);
  const auto attributes = fieldAttributes (sphere);
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZRGB>> ();
  auto polygons = std::make_shared<std::vector<pcl::Vertices>> ();
  for (std::size_t v = 0; v < sphere.vertices.size (); ++v)
  {
    pcl::PointXYZRGB p;
    p.getVector3fMap () = sphere.vertices[v].cast<float> ();
    p.r = static_cast<std::uint8_t> (std::lround (attributes->values (v, 0)));
    p.g = static_cast<std::uint8_t> (std::lround (attributes->values (v, 1)));
    p.b = 50;
    cloud->push_back (p);
  }
  for (const Eigen::Vector3i& t : sphere.triangles)
  {
    pcl::Vertices polygon;
    polygon.vertices = {t[0], t[1], t[2]};
    polygons->push_back (polygon);
  }
  SparseSurfaceEncoder<pcl::PointXYZRGB> encoder;
  encoder.setInputCloud (cloud);
  encoder.setInputPolygons (polygons);
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  ASSERT_EQ (model->attribute_channels.size (), 3u);  // r g b; PointXYZRGB's alpha is not a channel
  EXPECT_EQ (model->attribute_channels[2].channel, AttributeChannel::Blue);

  const auto rgb = resample<pcl::PointXYZRGB> (model, 5000);
  double mean = 0.0;
  for (const auto& point : rgb)
  {
    const Eigen::Vector4d expected = field (point.getVector3fMap ().cast<double> ());
    mean += (std::abs (point.r - expected[0]) + std::abs (point.g - expected[1])) / (2.0 * rgb.size ());
    ASSERT_EQ (point.b, 50);
  }
  EXPECT_LT (mean, 1.5);

  // Cropping with setIndices takes the indexed points' colours: the same model as the cropped mesh's.
  auto upper = std::make_shared<pcl::Indices> ();
  for (std::size_t v = 0; v < sphere.vertices.size (); ++v)
    if (sphere.vertices[v].z () > -0.2)
      upper->push_back (static_cast<int> (v));
  encoder.setIndices (upper);
  SparseSurfaceModel cropped;
  encoder.compute (cropped);
  ASSERT_EQ (cropped.attribute_channels.size (), 3u);
  const Eigen::MatrixXf at_vertices = cropped.reconstructVertexAttributes (upper->size ());
  // The cropped 642-vertex sphere is over CR 1, so the compression bound gives it fewer, larger patches
  // (SparseSurfaceEncoderOptions::max_compression_ratio), whose colour codes miss by up to 3.03 (3.0 before).
  for (std::size_t i = 0; i < upper->size (); i += 37)
    EXPECT_NEAR (at_vertices (static_cast<Eigen::Index> (i), 0), (*cloud)[(*upper)[i]].r, 3.5) << i;
}

TEST (Attributes, IntensityCloudAndMeshWithoutAttributes)
{
  const TriangleMesh sphere = makeIcosphere (3);
  const auto cloud = intensityCloud (sphere);
  const auto polygons = cloudPolygons (sphere);
  SparseSurfaceEncoder<pcl::PointXYZI> encoder;
  encoder.setInputCloud (cloud);
  encoder.setInputPolygons (polygons);
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  ASSERT_EQ (model->attribute_channels.size (), 1u);
  EXPECT_EQ (model->attribute_channels[0].channel, AttributeChannel::Intensity);
  const auto out = resample<pcl::PointXYZINormal> (model, 5000);
  double mean = 0.0;
  for (const auto& point : out)
    mean += std::abs (point.intensity - 1000.0 * point.z) / out.size ();
  EXPECT_LT (mean, 10.0);  // of a range of 2000

  // The library's mesh input has no attributes unless they are set.
  SparseSurfaceEncoder<pcl::PointXYZI> mesh_encoder;
  mesh_encoder.setInputMesh (std::make_shared<TriangleMesh> (sphere));
  SparseSurfaceModel plain;
  mesh_encoder.compute (plain);
  EXPECT_FALSE (plain.hasAttributes ());
}

// A point in no polygon (an organized cloud's invalid pixel, here NaN with a sensor's sentinel intensity)
// is no part of the surface: it must not set the intensity's range, which scales the coding tolerance.
TEST (Attributes, PointsInNoFaceDoNotWidenTheIntensityRange)
{
  const TriangleMesh sphere = makeIcosphere (3);
  const auto cloud = intensityCloud (sphere);
  const float lowest = std::min_element (cloud->begin (), cloud->end (), [] (const auto& a, const auto& b) {
                         return a.intensity < b.intensity;
                       })->intensity;
  const float highest = std::max_element (cloud->begin (), cloud->end (), [] (const auto& a, const auto& b) {
                          return a.intensity < b.intensity;
                        })->intensity;
  pcl::PointXYZI invalid;
  invalid.x = invalid.y = invalid.z = std::numeric_limits<float>::quiet_NaN ();
  invalid.intensity = 1e6f;
  cloud->push_back (invalid);
  SparseSurfaceEncoder<pcl::PointXYZI> encoder;
  encoder.setInputCloud (cloud);
  encoder.setInputPolygons (cloudPolygons (sphere));
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  ASSERT_EQ (model->attribute_channels.size (), 1u);
  EXPECT_EQ (model->attribute_channels[0].lower, lowest);
  EXPECT_EQ (model->attribute_channels[0].upper, highest);
  // Measured 4.45 (as without the point); the range up to 1e6 coded the intensity away (500, all of it).
  const auto out = resample<pcl::PointXYZINormal> (model, 5000);
  double mean = 0.0;
  for (const auto& point : out)
    mean += std::abs (point.intensity - 1000.0 * point.z) / out.size ();
  EXPECT_LT (mean, 6.5);
}

TEST (Attributes, BadAttributesAreRefused)
{
  const TriangleMesh sphere = makeIcosphere (2);
  auto attributes = fieldAttributes (sphere);
  auto wrong_rows = std::make_shared<VertexAttributes> (*attributes);
  wrong_rows->values.conservativeResize (10, 4);
  EXPECT_THROW (encode (sphere, wrong_rows), Error);
  // The stage fills a missing value (MissingValuesTakeTheNearestPointsValue); the mathematics refuses one.
  VertexAttributes nan = *attributes;
  nan.values (3, 3) = std::nanf ("");
  SparseSurfaceModel model;
  EXPECT_EQ (pcl_sparse_test::errorMessage ([&] {
               encodeSurface (sphere, nan, buildMeshTopology (sphere), SparseSurfaceEncoderOptions (),
                              makeCosineBasis (CosineBasisKind::DctQuadric, 12), 1, {}, model);
             }),
             "SparseSurfaceEncoder: attribute 'intensity' of vertex 3 is not a number (fillAttributeGaps gives such "
             "values their nearest vertex's)");
  auto twice = std::make_shared<VertexAttributes> (*attributes);
  twice->channels[1] = AttributeChannel::Red;
  EXPECT_THROW (encode (sphere, twice), Error);
  auto bright = std::make_shared<VertexAttributes> (*attributes);
  bright->values (0, 0) = 300.0f;
  EXPECT_THROW (encode (sphere, bright), Error);
}

TEST (Attributes, MissingValuesTakeTheNearestPointsValue)
{
  // Intensity: vertex 1 is nearer vertex 0 (1) than 2 (1.5); vertex 3 is 1.5 from both 2 and 5 (the lower
  // number wins); vertex 4 has no position and takes the first value. Red has a value only at vertex 4.
  const float nan = std::numeric_limits<float>::quiet_NaN ();
  const std::vector<Eigen::Vector3d> positions = {{0, 0, 0}, {1, 0, 0}, {2.5, 0, 0}, {4, 0, 0},
                                                  {std::nan (""), 0, 0}, {5.5, 0, 0}};
  VertexAttributes attributes;
  attributes.channels = {AttributeChannel::Red, AttributeChannel::Intensity};
  attributes.values.resize (6, 2);
  attributes.values.col (0) << nan, nan, nan, nan, 100.0f, nan;
  attributes.values.col (1) << 10.0f, nan, 30.0f, nan, nan, 60.0f;
  const AttributeGaps gaps = fillAttributeGaps (attributes, positions);
  EXPECT_EQ (gaps.filled, 3u);
  ASSERT_EQ (gaps.dropped.size (), 1u);
  EXPECT_EQ (gaps.dropped[0], AttributeChannel::Red);
  ASSERT_EQ (attributes.channels.size (), 1u);
  EXPECT_EQ (attributes.channels[0], AttributeChannel::Intensity);
  ASSERT_EQ (attributes.values.cols (), 1);
  const std::vector<float> expected = {10, 10, 30, 30, 10, 60};
  for (Eigen::Index v = 0; v < 6; ++v)
    EXPECT_EQ (attributes.values (v, 0), expected[static_cast<std::size_t> (v)]) << v;
  EXPECT_THROW (fillAttributeGaps (attributes, {{0, 0, 0}}), Error);  // rows and positions differ

  // Through the stage: a cloud with one NaN intensity codes as the cloud where that point has its nearest
  // point's intensity; a cloud whose intensities are all NaN codes the geometry alone.
  const TriangleMesh sphere = makeIcosphere (3);
  const auto cloud = intensityCloud (sphere);
  const auto polygons = cloudPolygons (sphere);
  const auto encodeCloud = [&] (const pcl::PointCloud<pcl::PointXYZI>::ConstPtr& input, AttributeGaps& found) {
    SparseSurfaceEncoder<pcl::PointXYZI> encoder;
    encoder.setInputCloud (input);
    encoder.setInputPolygons (polygons);
    SparseSurfaceModel model;
    encoder.compute (model);
    found = encoder.getAttributeGaps ();
    return model;
  };
  // A vertex whose nearest vertex is nearer than the second by 1 % (no tie for float rounding to break).
  std::size_t missing = 0, nearest = 0;
  for (; missing < sphere.vertices.size (); ++missing)
  {
    std::vector<std::pair<double, std::size_t>> by_distance;
    for (std::size_t v = 0; v < sphere.vertices.size (); ++v)
      if (v != missing)
        by_distance.emplace_back ((sphere.vertices[v] - sphere.vertices[missing]).norm (), v);
    std::partial_sort (by_distance.begin (), by_distance.begin () + 2, by_distance.end ());
    nearest = by_distance[0].second;
    if (by_distance[1].first > 1.01 * by_distance[0].first)
      break;
  }
  ASSERT_LT (missing, sphere.vertices.size ());
  auto with_nan = std::make_shared<pcl::PointCloud<pcl::PointXYZI>> (*cloud);
  (*with_nan)[missing].intensity = nan;
  auto filled_by_hand = std::make_shared<pcl::PointCloud<pcl::PointXYZI>> (*cloud);
  (*filled_by_hand)[missing].intensity = (*cloud)[nearest].intensity;
  AttributeGaps found, none;
  EXPECT_EQ (encodeModel (encodeCloud (with_nan, found)), encodeModel (encodeCloud (filled_by_hand, none)));
  EXPECT_EQ (found.filled, 1u);
  EXPECT_TRUE (found.dropped.empty ());
  EXPECT_EQ (none.filled, 0u);

  auto all_nan = std::make_shared<pcl::PointCloud<pcl::PointXYZI>> (*cloud);
  for (auto& p : *all_nan)
    p.intensity = nan;
  AttributeGaps all;
  EXPECT_FALSE (encodeCloud (all_nan, all).hasAttributes ());
  ASSERT_EQ (all.dropped.size (), 1u);
  EXPECT_EQ (all.dropped[0], AttributeChannel::Intensity);
}

// A channel of one huge value: the quantised file's budget was 1e-4 of a unit, and writing failed
// ("coefficient too large for the tolerance"); it is never finer than the values' float precision now.
TEST (Attributes, AHugeConstantIntensityIsWrittenQuantised)
{
  const TriangleMesh sphere = makeIcosphere (2);
  for (const float value : {1e30f, -3e38f})
  {
    auto attributes = std::make_shared<VertexAttributes> ();
    attributes->channels = {AttributeChannel::Intensity};
    attributes->values = Eigen::MatrixXf::Constant (static_cast<Eigen::Index> (sphere.vertices.size ()), 1, value);
    const SparseSurfaceModel::Ptr model = encode (sphere, attributes);
    ModelWriteOptions options;
    options.tolerance = 1e-4;
    std::vector<std::uint8_t> bytes;
    ASSERT_NO_THROW (bytes = encodeModel (*model, options)) << value;
    const auto decoded = std::make_shared<const SparseSurfaceModel> (decodeModel (bytes.data (), bytes.size ()));
    const auto cloud = resample<pcl::PointXYZINormal> (decoded, 1000);
    ASSERT_EQ (cloud.size (), 1000u);
    for (const auto& p : cloud)
      ASSERT_NEAR (p.intensity / value, 1.0f, 1e-6f) << value;
  }
}

TEST (Attributes, ModelFileKeepsTheColours)
{
  const TriangleMesh sphere = makeIcosphere (4);
  const auto model = encode (sphere, fieldAttributes (sphere));
  const auto plain = encode (sphere, nullptr);
  const auto rgb = resample<pcl::PointXYZRGBNormal> (model, 5000);

  // Lossless: the same cloud, colours included, bit for bit.
  const auto bytes = encodeModel (*model);
  const auto loaded = std::make_shared<SparseSurfaceModel> (decodeModel (bytes.data (), bytes.size ()));
  const auto again = resample<pcl::PointXYZRGBNormal> (loaded, 5000);
  ASSERT_EQ (again.size (), rgb.size ());
  for (std::size_t i = 0; i < rgb.size (); ++i)
  {
    ASSERT_EQ (again[i].getVector3fMap (), rgb[i].getVector3fMap ());
    ASSERT_EQ (again[i].rgba, rgb[i].rgba);
  }

  // Quantised (1e-4 of the diagonal, colour within 1/2 grey level): still within a few grey levels of the field.
  ModelWriteOptions options;
  options.tolerance = 1e-4;
  const auto small = encodeModel (*model, options);
  const auto quantised = std::make_shared<SparseSurfaceModel> (decodeModel (small.data (), small.size ()));
  const auto coarse = resample<pcl::PointXYZRGBNormal> (quantised, 5000);
  const auto intensity = resample<pcl::PointXYZINormal> (quantised, 5000);
  const FieldError e = colourError (coarse, intensity);
  EXPECT_LT (e.mean, 1.2);
  EXPECT_LT (e.max, 6.0);
  const double m = static_cast<double> (model->numPatches ());
  std::printf ("sphere, %zu patches: attribute bytes per patch %.1f lossless, %.1f quantised (file %zu / %zu bytes)\n",
               model->numPatches (), (bytes.size () - encodeModel (*plain).size ()) / m,
               (small.size () - encodeModel (*plain, options).size ()) / m, bytes.size (), small.size ());
}

// A scan (a cloud without polygons) carries its colours too: surface vertex v is input point
// getSurfaceInputIndices ()[v], so the colours of the points cleaning drops never leak in.
TEST (Attributes, ScanWithColourGivesTheColoursAutomatically)
{
  const int width = 80, height = 60;
  const double f = 60.0;
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZRGB>> (width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
    {
      pcl::PointXYZRGB& p = cloud->at (x, y);
      p.r = p.g = p.b = 255;
      if ((x * 7 + y * 3) % 23 == 0)  // NaN pixels, white
      {
        p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN ();
        continue;
      }
      const double z = 2.0 + 0.1 * std::sin (0.1 * x);
      p.x = static_cast<float> ((x - 0.5 * width) / f * z);
      p.y = static_cast<float> ((y - 0.5 * height) / f * z);
      p.z = static_cast<float> (z);
      p.r = static_cast<std::uint8_t> (std::lround (128.0 + 80.0 * p.x));
      p.g = static_cast<std::uint8_t> (std::lround (128.0 + 80.0 * p.y));
      p.b = 50;
    }
  cloud->is_dense = false;
  SparseSurfaceEncoder<pcl::PointXYZRGB> encoder;
  encoder.setInputCloud (cloud);
  auto model = std::make_shared<SparseSurfaceModel> ();
  encoder.compute (*model);
  ASSERT_EQ (model->attribute_channels.size (), 3u);
  ASSERT_LT (encoder.getSurfaceInputIndices ().size (), cloud->size ());  // NaN pixels dropped

  const auto rgb = resample<pcl::PointXYZRGB> (model, 5000);
  double mean = 0.0;
  for (const auto& point : rgb)
  {
    mean += (std::abs (point.r - (128.0 + 80.0 * point.x)) + std::abs (point.g - (128.0 + 80.0 * point.y))) /
            (2.0 * rgb.size ());
    ASSERT_EQ (point.b, 50);
  }
  EXPECT_LT (mean, 1.5);

  // Opting out: empty attributes code the geometry only.
  encoder.setVertexAttributes (std::make_shared<VertexAttributes> ());
  SparseSurfaceModel geometry;
  encoder.compute (geometry);
  EXPECT_FALSE (geometry.hasAttributes ());
  EXPECT_EQ (encodeModel (geometry), encodeModel (geometryOf (*model)));  // the same geometry, byte for byte

  // The same scan through setInputScan gives the same model.
  auto scan = std::make_shared<ScanCloud> ();
  toScanCloud (*cloud, *scan);
  SparseSurfaceEncoder<pcl::PointXYZ> scan_encoder;
  scan_encoder.setInputScan (scan);
  SparseSurfaceModel from_scan;
  scan_encoder.compute (from_scan);
  EXPECT_EQ (encodeModel (from_scan), encodeModel (*model));
}

// The attribute coder takes its dictionary from the height's where that holds its atoms (the default
// bases: the quadric's cosines are the Dct atoms), never from a basis with other functions: either way
// the codes are those of its own dictionary, to the bit.
TEST (Attributes, CodesDoNotDependOnTheHeightDictionary)
{
  const int num_points = 60;
  Patch patch;
  std::vector<Eigen::Vector2d> positions;
  VertexAttributes values;
  values.channels = {AttributeChannel::Red, AttributeChannel::Green, AttributeChannel::Blue};
  values.values.resize (num_points, 3);
  for (int i = 0; i < num_points; ++i)
  {
    patch.vertices.push_back (i);
    // A deterministic scatter over the unit square.
    const Eigen::Vector2d p (std::fmod (0.618034 * i, 1.0) * 2.0 - 1.0, std::fmod (0.754878 * i, 1.0) * 2.0 - 1.0);
    positions.push_back (p);
    values.values.row (i) << static_cast<float> (128.0 + 90.0 * std::sin (2.0 * p.x ())),
      static_cast<float> (100.0 + 40.0 * p.x () * p.y ()), static_cast<float> (60.0 + 30.0 * std::cos (3.0 * p.y ()));
  }
  AttributeCodingInput input;
  input.values = &values;
  input.channels = values.channelInfo ();
  input.basis = makeCosineBasis (CosineBasisKind::Dct);
  input.options.tolerance = 0.0;  // every allowed atom is a candidate to the end: any column mix-up shows
  const double spacing = 0.6;     // the Nyquist cap leaves the cosines up to frequency 6
  const std::vector<SparseCode> own = codePatchAttributes (patch, positions, {}, spacing, input);
  ASSERT_EQ (own.size (), 3u);
  for (const SparseCode& code : own)
    ASSERT_EQ (code.atoms.size (), 12u);

  for (const CosineBasisKind height_kind : {CosineBasisKind::DctQuadric, CosineBasisKind::Dct, CosineBasisKind::Paper})
  {
    SCOPED_TRACE (cosineBasisKindName (height_kind));
    // The attribute atoms' indices (the monomials after them): the paper's atoms under the same indices
    // are other functions, and must not be taken.
    const CosineAtoms::ConstPtr height = makeCosineBasis (height_kind);
    const std::vector<char> allowed = nyquistAllowedAtoms (*input.basis, spacing, input.nyquist_factor, input.nyquist_rule);
    std::vector<int> atoms = allowedAtomIndices (allowed);
    ASSERT_LT (atoms.size (), allowed.size ());
    for (int m = 0; m < height->monomials (); ++m)
      atoms.push_back (static_cast<int> (allowed.size ()) + m);
    Eigen::MatrixXd matrix;
    height->evaluate (positions, atoms, matrix);
    const CodingDictionary dictionary{height.get (), &atoms, &matrix};
    const std::vector<SparseCode> shared = codePatchAttributes (patch, positions, {}, spacing, input, &dictionary);
    ASSERT_EQ (shared.size (), own.size ());
    for (std::size_t c = 0; c < own.size (); ++c)
    {
      EXPECT_EQ (shared[c].atoms, own[c].atoms);
      EXPECT_EQ (shared[c].coefficients, own[c].coefficients);
    }
  }
}
