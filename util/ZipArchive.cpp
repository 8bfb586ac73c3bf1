#include "util/ZipArchive.h"

#include <zip.h>

#include <algorithm>
#include <cstdio>

#include "util/Error.h"
#include "util/TextEncoding.h"

namespace candela {

namespace {

[[noreturn]] void fail(const std::string& message) {
    throw InputError(oneLine(message));
}

std::string megabytes(uint64_t bytes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f MB", double(bytes) / double(1 << 20));
    return buf;
}

}  // namespace

ZipArchive::ZipArchive(const std::string& bytes, const std::string& path, const std::string& kind)
    : mPath(path) {
    zip_error_t error;
    zip_error_init(&error);
    zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
    if (source) mZip = zip_open_from_source(source, ZIP_RDONLY, &error);
    if (!mZip) {
        std::string why = zip_error_strerror(&error);
        zip_error_fini(&error);
        if (source) zip_source_free(source);
        fail(path + ": not " + kind + " (a ZIP archive): " + why);
    }
    zip_error_fini(&error);
    zip_int64_t count = zip_get_num_entries(mZip, 0);
    for (zip_int64_t i = 0; i < count; ++i) {
        const char* raw = zip_get_name(mZip, zip_uint64_t(i), ZIP_FL_ENC_RAW);
        std::string name = raw ? raw : "";
        mNames.push_back(isValidUtf8(name) ? name : fromCodePage850(name));
    }
}

ZipArchive::~ZipArchive() {
    zip_discard(mZip);
}

int64_t ZipArchive::find(const std::string& name) const {
    auto it = std::find(mNames.begin(), mNames.end(), name);
    return it == mNames.end() ? -1 : int64_t(it - mNames.begin());
}

std::string ZipArchive::read(int64_t index, const std::string& label) const {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(mZip, zip_uint64_t(index), 0, &st) != 0)
        fail(mPath + ": " + label + ": cannot be read (" + zip_strerror(mZip) + ")");
    if ((st.valid & ZIP_STAT_SIZE) && st.size > kMaxZipMember)
        fail(mPath + ": " + label + ": " + megabytes(st.size) + " uncompressed, more than the " +
             megabytes(kMaxZipMember) + " a member may hold");
    zip_file_t* file = zip_fopen_index(mZip, zip_uint64_t(index), 0);
    if (!file) fail(mPath + ": " + label + ": cannot be read (" + zip_strerror(mZip) + ")");
    std::string out;
    char buffer[65536];
    while (true) {
        zip_int64_t n = zip_fread(file, buffer, sizeof buffer);
        if (n < 0) {
            std::string why = zip_file_strerror(file);
            zip_fclose(file);
            fail(mPath + ": " + label + ": damaged (" + why + ")");
        }
        if (n == 0) break;
        out.append(buffer, size_t(n));
        // A size field can lie; what is inflated is bounded all the same.
        if (out.size() > kMaxZipMember) {
            zip_fclose(file);
            fail(mPath + ": " + label + ": more than the " + megabytes(kMaxZipMember) +
                 " a member may hold");
        }
    }
    zip_fclose(file);
    if ((st.valid & ZIP_STAT_SIZE) && out.size() != st.size)
        fail(mPath + ": " + label + ": truncated (" + std::to_string(out.size()) +
             " bytes of the " + std::to_string(st.size) + " its entry declares)");
    return out;
}

}  // namespace candela
