/// libFuzzer target for the mesh and scan readers (.obj .off .ply .stl .pcd .xyz): the first byte picks the
/// format (byte % 6) and a loader option (byte / 6 odd or even), the rest is the file. Any input must
/// either load or throw pcl_sparse::Error; sanitizers (ASan, UBSan) turn anything else into a finding. A
/// loaded mesh must index only its own vertices, a loaded scan must number every point. Meshes are read
/// again by MeshStreamReader in small chunks (the streamed binary PLY reader of tiled inputs): its faces
/// too must index only its vertices, and where both readers accept a file they give the same counts. Built by
/// bench/fuzz.sh (target inputs; clang, -fsanitize=fuzzer,address,undefined); seed corpus from
/// make_input_corpus.py.

#include <pcl_sparse/common/error.h>
#include <pcl_sparse/io/mesh_io.h>
#include <pcl_sparse/io/mesh_stream.h>
#include <pcl_sparse/io/scan_io.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>
#include <unistd.h>

namespace
{
  const char* const extensions[] = {".obj", ".off", ".ply", ".stl", ".pcd", ".xyz"};

  /// The readers take paths: each input is written to one file per process and format.
  std::string
  writeInput (const std::uint8_t* data, std::size_t size, const char* extension)
  {
    const std::string path = "/tmp/fuzz_input_" + std::to_string (::getpid ()) + extension;
    std::FILE* file = std::fopen (path.c_str (), "wb");
    if (!file)
      std::abort ();
    if (size > 0 && std::fwrite (data, 1, size, file) != size)
      std::abort ();
    std::fclose (file);
    return path;
  }
} // namespace

extern "C" int
LLVMFuzzerTestOneInput (const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
    return 0;
  const int format = data[0] % 6;
  const std::string path = writeInput (data + 1, size - 1, extensions[format]);
  if (format < 4)
  {
    pcl_sparse::MeshLoadOptions options;
    options.allow_no_faces = (data[0] / 6) % 2 == 1;
    try
    {
      const pcl_sparse::TriangleMesh mesh = pcl_sparse::loadTriangleMesh (path, options);
      for (const Eigen::Vector3i& triangle : mesh.triangles)
        if (triangle.minCoeff () < 0 || triangle.maxCoeff () >= static_cast<int> (mesh.vertices.size ()))
          std::abort ();
    }
    catch (const pcl_sparse::Error&)
    {
    }
  }
  if (format < 4)
  {
    std::size_t vertices = 0, triangles = 0;
    bool streamed = false;
    try
    {
      pcl_sparse::MeshStreamReader reader (path);
      std::vector<Eigen::Vector3d> vertex_chunk;
      while (reader.readVertices (vertex_chunk, 7))
        vertices += vertex_chunk.size ();
      if (vertices != reader.numVertices ())
        std::abort ();
      std::vector<Eigen::Vector3i> triangle_chunk;
      while (reader.readTriangles (triangle_chunk, 5))
      {
        for (const Eigen::Vector3i& triangle : triangle_chunk)
          if (triangle.minCoeff () < 0 || static_cast<std::size_t> (triangle.maxCoeff ()) >= vertices)
            std::abort ();
        triangles += triangle_chunk.size ();
      }
      streamed = true;
    }
    catch (const pcl_sparse::Error&)
    {
    }
    if (streamed)
    {
      try
      {
        const pcl_sparse::TriangleMesh mesh = pcl_sparse::loadTriangleMesh (path);
        if (mesh.vertices.size () != vertices || mesh.triangles.size () != triangles)
          std::abort ();
      }
      catch (const pcl_sparse::Error&)
      {
      }
    }
  }
  {  // the scan loader reads every format, meshes as their vertices
    pcl_sparse::ScanLoadOptions options;
    options.clean = (data[0] / 6) % 2 == 0;
    try
    {
      pcl_sparse::ScanCloud scan;
      pcl_sparse::loadScanCloud (path, scan, options);
      if (scan.indices.size () != scan.positions.size ())
        std::abort ();
    }
    catch (const pcl_sparse::Error&)
    {
    }
  }
  std::remove (path.c_str ());
  return 0;
}
