#include "io/exr_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>

#include "io/atomic_write.h"

namespace rr {

namespace {
// The most values (pixels × channels) readExr allocates for: 2^28 floats, 1 GiB. A larger
// image is a damaged header, not one this project reads.
constexpr int64_t kMaxValues = int64_t(1) << 28;

// Every header attribute's declared size fits in the file. Debian's OpenEXR 3.1 allocates an
// attribute's declared size before reading it: `make fuzz` found a 123-byte file declaring a
// 2 GB string that took 2 GiB and seconds to refuse (tests/fuzz/regressions/exr/). The walk
// follows the file layout (magic, version and flags, then each part's attributes as name, type,
// 32-bit size and value, each part's list ended by an empty name); OpenEXR checks the rest.
void checkAttributeSizes(const std::filesystem::path& file) {
    constexpr size_t kHeaderBytes = size_t(1) << 20;  // headers past this go unchecked
    const uint64_t fileSize = std::filesystem::file_size(file);
    std::string bytes(size_t(std::min<uint64_t>(fileSize, kHeaderBytes)), '\0');
    std::ifstream(file, std::ios::binary).read(bytes.data(), std::streamsize(bytes.size()));
    if (bytes.size() < 8 || bytes.compare(0, 4, "\x76\x2f\x31\x01") != 0)
        return;                                       // OpenEXR says why
    const bool multipart = uint8_t(bytes[5]) & 0x10;  // bit 12 of the little-endian version field
    size_t at = 8;
    // The next null-terminated name, or nullopt where the checked bytes end.
    auto name = [&]() -> std::optional<std::string> {
        const size_t end = bytes.find('\0', at);
        if (end == std::string::npos) return std::nullopt;
        std::string text = bytes.substr(at, end - at);
        at = end + 1;
        return text;
    };
    for (;;) {  // each part's header
        int attributes = 0;
        for (;;) {
            const auto attribute = name();
            if (!attribute) return;
            if (attribute->empty()) break;
            if (!name() || bytes.size() - at < 4) return;  // the type, the size
            uint32_t size = 0;
            for (int k = 3; k >= 0; --k)
                size = size << 8 | uint8_t(bytes[at + size_t(k)]);
            at += 4;
            if (size > fileSize - at)
                throw std::runtime_error("malformed header: attribute \"" + *attribute + "\" of " +
                                         std::to_string(size) + " bytes in a file of " +
                                         std::to_string(fileSize));
            if (size > bytes.size() - at) return;
            at += size;
            ++attributes;
        }
        if (!multipart || attributes == 0) return;
    }
}
}  // namespace

void writeExr(const std::filesystem::path& file, const ExrImage& image, int threads) {
    // OpenEXR's thread pool is process-wide: widen it for this write only.
    const int previousThreads = Imf::globalThreadCount();
    if (threads > previousThreads) Imf::setGlobalThreadCount(threads);
    struct RestoreThreads {
        int count;
        ~RestoreThreads() {
            if (Imf::globalThreadCount() != count) Imf::setGlobalThreadCount(count);
        }
    } restore{previousThreads};
    writeAtomically(file, [&](const std::filesystem::path& temporary) {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        // Deflate's level hardly matters on noisy floats: level 1 writes a 512² render 8 %
        // faster than the default 4, and its file is no larger (6.12 against 6.13 MB).
        header.zipCompressionLevel() = 1;
        for (const auto& [name, value] : image.attributes) {
            if (const auto* s = std::get_if<std::string>(&value))
                header.insert(name, Imf::StringAttribute(*s));
            else if (const auto* i = std::get_if<int>(&value))
                header.insert(name, Imf::IntAttribute(*i));
            else
                header.insert(name, Imf::DoubleAttribute(std::get<double>(value)));
        }
        Imf::FrameBuffer frame;
        for (const auto& [name, data] : image.channels) {
            if (data.size() != size_t(image.width) * image.height)
                throw std::logic_error("EXR channel " + name + " has the wrong size");
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            frame.insert(name, Imf::Slice(Imf::FLOAT, (char*)data.data(), sizeof(float),
                                          sizeof(float) * image.width));
        }
        Imf::OutputFile out(temporary.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(image.height);
    });
}

ExrImage readExr(const std::filesystem::path& file) {
    try {
        checkAttributeSizes(file);
        Imf::InputFile in(file.c_str());
        const Imath::Box2i window = in.header().dataWindow();
        // In 64 bits: a damaged header's window can span more than an int holds.
        const int64_t width = int64_t(window.max.x) - window.min.x + 1;
        const int64_t height = int64_t(window.max.y) - window.min.y + 1;
        int64_t channels = 0;
        for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it)
            ++channels;
        if (width < 1 || height < 1 || width * height > kMaxValues / std::max<int64_t>(channels, 1))
            throw std::runtime_error("data window of " + std::to_string(width) + " x " +
                                     std::to_string(height) + " pixels and " +
                                     std::to_string(channels) + " channels is too large");
        ExrImage image;
        image.width = static_cast<int>(width);
        image.height = static_cast<int>(height);
        Imf::FrameBuffer frame;
        for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) {
            std::vector<float>& data = image.channels[it.name()];
            data.resize(size_t(width * height));
            frame.insert(it.name(), Imf::Slice::Make(Imf::FLOAT, data.data(), window));
        }
        in.setFrameBuffer(frame);
        in.readPixels(window.min.y, window.max.y);
        for (auto it = in.header().begin(); it != in.header().end(); ++it) {
            const Imf::Attribute& a = it.attribute();
            if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a))
                image.attributes[it.name()] = s->value();
            else if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&a))
                image.attributes[it.name()] = i->value();
            else if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&a))
                image.attributes[it.name()] = d->value();
            else if (const auto* f = dynamic_cast<const Imf::FloatAttribute*>(&a))
                image.attributes[it.name()] = double(f->value());
        }
        return image;
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot read EXR " + file.string() + ": " + e.what());
    }
}

}  // namespace rr
