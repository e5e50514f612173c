// The OpenEXR plugin (io/openexr_io.h).

#include "io/openexr_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cmath>
#include <limits>
#include <new>
#include <vector>

#include "core/error.h"
#include "core/float32_range.h"
#include "core/parse.h"

namespace radrecon {

namespace {

/// 32-bit float R, G, B channels, as PFM holds them: half floats end at 65504 (a lamp of 1e5
/// W/m^2 was written as infinity) and flush what lies below 6e-8 to 0.
void write(const std::filesystem::path& file, const std::string& shown_as, const Image& image) {
  const int width = image.width(), height = image.height();
  const size_t n = static_cast<size_t>(width) * height;
  std::vector<float> pixels(n * 3);
  Float32Range range;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double v = image.at(x, y)[c];
        if (std::isfinite(v) && std::abs(v) > std::numeric_limits<float>::max())
          throw UserError(shown_as, "a value, " + format_number(v) +
                                        ", is beyond the range of OpenEXR's 32-bit floats (3.4e38)");
        range.add(v);
        pixels[(static_cast<size_t>(y) * width + x) * 3 + static_cast<size_t>(c)] = static_cast<float>(v);
      }
  range.refuse_underflow(shown_as, kImageFloat32Advice);
  try {
    Imf::Header header(width, height);
    const char* names[3] = {"R", "G", "B"};
    Imf::FrameBuffer frame;
    for (size_t c = 0; c < 3; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data() + c), sizeof(float) * 3,
                                        sizeof(float) * 3 * static_cast<size_t>(width)));
    }
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(height);
  } catch (const std::bad_alloc&) {
    throw;  // out of memory, not a file problem
  } catch (const std::exception& e) {
    throw UserError(shown_as, std::string("cannot write OpenEXR: ") + e.what());
  }
}

PictureValues read(const std::filesystem::path& path) {
  const std::string file = path.string();
  PictureValues p;
  p.format = FileFormat::exr;
  try {
    Imf::InputFile in(path.c_str());
    const Imath::Box2i dw = in.header().dataWindow();
    const long long width = static_cast<long long>(dw.max.x) - dw.min.x + 1,
                    height = static_cast<long long>(dw.max.y) - dw.min.y + 1;
    check_picture_size(width, height, file);
    const Imf::ChannelList& list = in.header().channels();
    std::vector<const char*> names;
    if (list.findChannel("R") && list.findChannel("G") && list.findChannel("B"))
      names = {"R", "G", "B"};
    else if (list.findChannel("Y"))
      names = {"Y"};
    else
      throw UserError(file, "OpenEXR: no R, G, B channels and no Y channel");
    if (!in.isComplete()) throw UserError(file, "OpenEXR: the file is incomplete (truncated)");
    p.width = static_cast<int>(width);
    p.height = static_cast<int>(height);
    p.channels = static_cast<int>(names.size());
    std::vector<float> buffer(static_cast<size_t>(width) * height * p.channels);
    Imf::FrameBuffer frame;
    for (size_t c = 0; c < names.size(); ++c)
      frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, buffer.data() + c, dw, sizeof(float) * p.channels,
                                              sizeof(float) * p.channels * static_cast<size_t>(width)));
    in.setFrameBuffer(frame);
    in.readPixels(dw.min.y, dw.max.y);
    p.values.assign(buffer.begin(), buffer.end());  // OpenEXR's y grows downward: row 0 is the top
  } catch (const UserError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw UserError(file, std::string("cannot read OpenEXR: ") + e.what());
  }
  return p;
}

}  // namespace

}  // namespace radrecon

extern "C" __attribute__((visibility("default"))) const void* radrecon_openexr_functions() {
  static const radrecon::OpenExrFunctions functions{radrecon::write, radrecon::read};
  return &functions;
}
