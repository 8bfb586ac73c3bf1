#pragma once
// Reading image files that users give (environment maps, light-field images) through
// OpenImageIO, safely for any bytes:
//  - only the reader that the file's extension names is used: OpenImageIO would otherwise try
//    every format it knows (DICOM, FITS, ...) on a file that is not what its extension says;
//  - an OpenEXR header attribute may not declare more bytes than the file holds, nor a value of
//    another length than OpenEXR reads for its type, nor its data window more pixels than the
//    caller accepts (OpenEXR 3.1 allocates what they declare before reading them, and reads a
//    fixed-size type's own length whatever the declaration, so a file whose declarations
//    disagree made it read an attribute that the check had skipped);
//  - the pixel buffer is not cleared before decoding, so its pages are touched only as rows
//    decode: a short file whose header claims a huge image fails after its first rows instead
//    of first clearing gigabytes;
//  - pixels are read in bands of rows in the file's own formats and converted here, through a
//    buffer sized to the band: OpenImageIO's own conversion allocates about 64 MB for any image.
//  Fuzzing found all four.

#include <memory>
#include <string>

namespace candela {

class ImageFileReader {
  public:
    /// Opens `path`; throws InputError "CONTEXT: cannot read image: REASON", or "CONTEXT: image
    /// size WxH out of range (1..MAX_SIDE per side)" for an empty image or one wider or higher
    /// than `maxSide` pixels (checked in an OpenEXR header before OpenEXR reads it).
    ImageFileReader(const std::string& path, const std::string& context, int maxSide);
    /// Reads an image held in memory (an image member of a container): `bytes` (kept by the
    /// caller while the reader lives) by the reader of `format` only, "png" or "jpeg" (others are
    /// refused: OpenEXR's header check above reads a file); the same size check and messages.
    struct InMemory {};
    ImageFileReader(InMemory, const std::string& bytes, const std::string& format,
                    const std::string& context, int maxSide);
    ~ImageFileReader();
    ImageFileReader(const ImageFileReader&) = delete;
    ImageFileReader& operator=(const ImageFileReader&) = delete;

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    int channels() const { return mChannels; }

    /// All pixels as float, the first `channels` (at most channels()) per pixel, rows top to
    /// bottom. Throws InputError "CONTEXT: cannot read pixels: REASON".
    std::unique_ptr<float[]> readPixels(int channels);

  private:
    /// Takes the opened image's size; refuses one outside 1..maxSide per side.
    void takeSize(int maxSide);
    struct Input;
    std::unique_ptr<Input> mInput;
    std::string mContext;
    int mWidth = 0, mHeight = 0, mChannels = 0;
};

}  // namespace candela
