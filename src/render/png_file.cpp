#include <pcl_sparse/render/png_file.h>

#include <pcl_sparse/common/atomic_write.h>
#include <pcl_sparse/common/error.h>

#include <png.h>

#include <cstring>

namespace pcl_sparse
{
  std::vector<std::uint8_t>
  encodePng (const RgbImage& image)
  {
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size () != static_cast<std::size_t> (image.width) * image.height * 3)
      throw Error ("encodePng: empty or inconsistent image");
    // libpng's simplified API: no setjmp in our code, and it writes no time stamp (bytes depend on pixels only).
    png_image png;
    std::memset (&png, 0, sizeof (png));
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32> (image.width);
    png.height = static_cast<png_uint_32> (image.height);
    png.format = PNG_FORMAT_RGB;
    png_alloc_size_t size = 0;
    const png_int_32 stride = image.width * 3;
    if (!png_image_write_to_memory (&png, nullptr, &size, 0, image.pixels.data (), stride, nullptr))
      throw Error (std::string ("encodePng: ") + png.message);
    std::vector<std::uint8_t> bytes (size);
    if (!png_image_write_to_memory (&png, bytes.data (), &size, 0, image.pixels.data (), stride, nullptr))
      throw Error (std::string ("encodePng: ") + png.message);
    bytes.resize (size);
    png_image_free (&png);
    return bytes;
  }

  void
  savePng (const std::string& path, const RgbImage& image)
  {
    std::vector<std::uint8_t> bytes;
    try
    {
      bytes = encodePng (image);
    }
    catch (const Error& e)
    {
      throw Error (path + ": " + e.what ());
    }
    writeBytesAtomically (path, bytes.data (), bytes.size ());
  }
} // namespace pcl_sparse
