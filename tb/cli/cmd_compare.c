/* saarcor compare A B: image difference metrics through OpenImageIO (host/image/img.h). */
#define _GNU_SOURCE
#include <getopt.h>
#include <math.h>
#include <stdio.h>

#include "cli.h"
#include "img.h"

int cmd_compare(int argc, char **argv)
{
    static const struct option opts[] = {
        { "diff", required_argument, NULL, 'd' }, { "psnr-min", required_argument, NULL, 'p' },
        { "threshold", required_argument, NULL, 't' }, { "help", no_argument, NULL, 'h' }, { 0, 0, 0, 0 }
    };
    const char *diff = NULL;
    double psnr_min = -INFINITY, threshold = 0.0;
    int have_min = 0, c;
    optind = 0;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "d:p:t:h", opts, NULL)) != -1) {
        switch (c) {
        case 'd': diff = optarg; break;
        case 'p':
            if (!cli_parse_double(optarg, &psnr_min))
                return cli_usage_error("compare", "bad --psnr-min '%s'", optarg);
            have_min = 1;
            break;
        case 't':
            if (!cli_parse_double(optarg, &threshold) || threshold < 0)
                return cli_usage_error("compare", "bad --threshold '%s'", optarg);
            break;
        case 'h':
            printf("usage: saarcor compare A B [--diff FILE] [--psnr-min DB] [--threshold T]\n\n"
                   "Compares two images of equal size (any format OpenImageIO reads; 8-bit values\n"
                   "scaled to [0,1]) and prints PSNR = 20 log10(1/RMS) over all channels, the mean and\n"
                   "maximum absolute error with its location, and the share of pixels where some\n"
                   "channel differs by more than T (default 0). --diff writes |A-B| as an image.\n"
                   "Exit 0, or 1 if the PSNR is below --psnr-min; 3 if an image cannot be read.\n");
            return SAARCOR_EXIT_OK;
        default: return cli_bad_option("compare", argc, argv);
        }
    }
    if (argc - optind != 2)
        return cli_usage_error("compare", "expected two images");
    if (cli_parse_only)
        return SAARCOR_EXIT_OK;
    img_compare_result r;
    char err[512];
    if (img_compare(argv[optind], argv[optind + 1], threshold, diff, &r, err, sizeof err) != 0) {
        cli_error("compare", "%s", err);
        return SAARCOR_EXIT_INPUT;
    }
    printf("psnr_db %.4f\nmean_abs_error %.6g\nrms_error %.6g\nmax_abs_error %.6g at (%d, %d) channel %d\n"
           "differing_pixels %llu of %llu (%.4f%%) over %.6g\n",
           r.psnr, r.mean_error, r.rms_error, r.max_error, r.max_x, r.max_y, r.max_channel,
           (unsigned long long)r.differing_pixels, (unsigned long long)r.pixels,
           r.pixels ? 100.0 * (double)r.differing_pixels / (double)r.pixels : 0.0, threshold);
    if (have_min && !(r.psnr >= psnr_min)) {
        printf("FAIL: psnr %.4f dB below %.4f dB\n", r.psnr, psnr_min);
        return SAARCOR_EXIT_FAIL;
    }
    if (have_min)
        printf("PASS: psnr %.4f dB >= %.4f dB\n", r.psnr, psnr_min);
    return SAARCOR_EXIT_OK;
}
