// The OpenEXR plugin (io/openexr_io.h).

#include "io/openexr_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfRgbaFile.h>

#include <new>
#include <vector>

#include "core/error.h"

namespace radrecon {

namespace {

void write(const std::filesystem::path& file, const std::string& shown_as, const Image& image) {
  const int width = image.width(), height = image.height();
  std::vector<Imf::Rgba> pixels(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Rgb& c = image.at(x, y);
      pixels[static_cast<size_t>(y) * width + x] =
          Imf::Rgba(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]), 1.0f);
    }
  try {
    Imf::RgbaOutputFile out(file.c_str(), width, height, Imf::WRITE_RGB);
    out.setFrameBuffer(pixels.data(), 1, static_cast<size_t>(width));
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
