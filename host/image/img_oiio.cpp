// OpenImageIO shim behind img.h: no C++ exception or OIIO type crosses into C. Its one export,
// img_oiio_api, is either linked in or loaded with libsaarcor_img.so (img.c says why).
#include "img_api.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <limits>
#include <string>

using namespace OIIO;

namespace {

void set_error(char *err, size_t errlen, const std::string &msg)
{
    if (!err || errlen == 0)
        return;
    std::string line = msg.substr(0, msg.find('\n')); // one line
    std::snprintf(err, errlen, "%s", line.c_str());
}

bool read_buf(const char *path, ImageBuf &buf, char *err, size_t errlen)
{
    buf.reset(path);
    if (!buf.read(0, 0, true, TypeDesc::FLOAT)) {
        set_error(err, errlen, std::string("cannot read image '") + path + "': " + buf.geterror());
        return false;
    }
    return true;
}

// SOURCE_DATE_EPOCH (the reproducible-builds convention: seconds since 1970) set: the file's
// DateTime is that time, not now, so two runs write the same bytes (a testbench compares them
// with cmp); unset, OpenImageIO's writers date the file as before.
void set_date(ImageSpec &spec)
{
    const char *epoch = std::getenv("SOURCE_DATE_EPOCH");
    char *end = nullptr;
    const long long s = epoch ? std::strtoll(epoch, &end, 10) : -1;
    if (!epoch || end == epoch || *end || s < 0)
        return;
    const std::time_t t = (std::time_t)s;
    std::tm tm;
    char date[32];
    if (gmtime_r(&t, &tm) && std::strftime(date, sizeof date, "%Y:%m:%d %H:%M:%S", &tm))
        spec.attribute("DateTime", date);
}

} // namespace

static int read_image(const char *path, img_t *out, char *err, size_t errlen)
{
    try {
        ImageBuf buf;
        if (!read_buf(path, buf, err, errlen))
            return -1;
        const ImageSpec &spec = buf.spec();
        const size_t n = (size_t)spec.width * spec.height * spec.nchannels;
        float *px = (float *)std::malloc(n * sizeof(float)); // img_free's free()
        if (!px) {
            set_error(err, errlen, "out of memory");
            return -1;
        }
        if (!buf.get_pixels(buf.roi(), TypeDesc::FLOAT, px)) {
            std::free(px);
            set_error(err, errlen, std::string("cannot read pixels of '") + path + "'");
            return -1;
        }
        out->width = spec.width;
        out->height = spec.height;
        out->channels = spec.nchannels;
        out->pixels = px;
        return 0;
    } catch (const std::exception &e) {
        set_error(err, errlen, e.what());
        return -1;
    }
}

// Writes float pixels into file (img.c's path.tmp), in the format of path's extension: create()
// picks the plugin by name, open() writes any file name. names == nullptr: 8-bit for formats
// without float pixels (PNG) and half floats otherwise (EXR); with channel names: full floats.
static int write_file(const char *path, const char *file, const img_t *img, const char *const *names, char *err,
                      size_t errlen)
{
    try {
        auto out = ImageOutput::create(path);
        if (!out) {
            set_error(err, errlen, std::string("cannot write '") + path + "': " + OIIO::geterror());
            return -1;
        }
        const TypeDesc type = names ? TypeDesc::FLOAT : out->supports("floatpixels") ? TypeDesc::HALF : TypeDesc::UINT8;
        ImageSpec spec(img->width, img->height, img->channels, type);
        set_date(spec);
        if (names) {
            spec.channelnames.clear();
            for (int c = 0; c < img->channels; c++)
                spec.channelnames.push_back(names[c]);
        }
        if (!out->open(file, spec) || !out->write_image(TypeDesc::FLOAT, img->pixels) || !out->close()) {
            set_error(err, errlen, std::string("cannot write '") + path + "': " + out->geterror());
            return -1;
        }
        return 0;
    } catch (const std::exception &e) {
        set_error(err, errlen, e.what());
        return -1;
    }
}

static int compare_images(const char *path_a, const char *path_b, double threshold, const char *diff_path,
                          img_compare_result *res, char *err, size_t errlen)
{
    try {
        ImageBuf a, b;
        if (!read_buf(path_a, a, err, errlen) || !read_buf(path_b, b, err, errlen))
            return -1;
        const ImageSpec &sa = a.spec(), &sb = b.spec();
        if (sa.width != sb.width || sa.height != sb.height || sa.nchannels != sb.nchannels) {
            char msg[256];
            std::snprintf(msg, sizeof msg, "images differ in size: %dx%dx%d vs %dx%dx%d", sa.width, sa.height,
                          sa.nchannels, sb.width, sb.height, sb.nchannels);
            set_error(err, errlen, msg);
            return -1;
        }
        const auto cr = ImageBufAlgo::compare(a, b, (float)threshold, (float)threshold);
        if (a.has_error() || b.has_error()) {
            set_error(err, errlen, "compare failed: " + a.geterror() + b.geterror());
            return -1;
        }
        res->mean_error = cr.meanerror;
        res->rms_error = cr.rms_error;
        res->psnr = cr.rms_error > 0 ? 20.0 * std::log10(1.0 / cr.rms_error)
                                     : std::numeric_limits<double>::infinity();
        res->max_error = cr.maxerror;
        res->max_x = cr.maxx;
        res->max_y = cr.maxy;
        res->max_channel = cr.maxc;
        res->pixels = (uint64_t)sa.width * sa.height;
        res->differing_pixels = cr.nfail;
        if (diff_path) {
            ImageBuf d = ImageBufAlgo::absdiff(a, b);
            if (d.has_error() || !d.write(diff_path)) {
                set_error(err, errlen, std::string("cannot write difference image '") + diff_path + "': " +
                                           d.geterror());
                return -1;
            }
        }
        return 0;
    } catch (const std::exception &e) {
        set_error(err, errlen, e.what());
        return -1;
    }
}

static const char *library_version(void) { return OIIO_VERSION_STRING; }

extern "C" const img_api *img_oiio_api(void)
{
    static const img_api api = { read_image, write_file, compare_images, library_version };
    return &api;
}
