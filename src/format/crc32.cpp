#include <pcl_sparse/format/crc32.h>

#include <array>

namespace pcl_sparse
{
  namespace
  {
    std::array<std::uint32_t, 256>
    makeTable ()
    {
      std::array<std::uint32_t, 256> table{};
      for (std::uint32_t n = 0; n < 256; ++n)
      {
        std::uint32_t c = n;
        for (int k = 0; k < 8; ++k)
          c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[n] = c;
      }
      return table;
    }
  } // namespace

  std::uint32_t
  crc32 (const std::uint8_t* data, std::size_t size)
  {
    static const std::array<std::uint32_t, 256> table = makeTable ();
    std::uint32_t c = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < size; ++i)
      c = table[(c ^ data[i]) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
  }
} // namespace pcl_sparse
