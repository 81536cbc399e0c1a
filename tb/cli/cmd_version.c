/* saarcor version: program version, fp24 format and which arithmetic path this build uses. */
#include <stdio.h>
#include <mpfr.h>

#include "cli.h"
#include "f24.h"
#include "img.h"
#include "version.h" /* generated: build/version.h */

#ifdef F24_FAST_SIM
#define F24_PATH "fast (binary64 + one rounding, bit-identical to the integer path)"
#else
#define F24_PATH "integer hardware reference"
#endif

int cmd_version(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        printf("usage: saarcor version\n\nPrints the program version, the fp24 number format of this build\n"
               "(1 sign, E exponent, M fraction bits), the arithmetic path and library versions.\n");
        return SAARCOR_EXIT_OK;
    }
    if (argc > 1)
        return cli_usage_error("version", "unexpected argument '%s'", argv[1]);
    printf("saarcor %s\n", SAARCOR_VERSION);
    printf("fp24 format: E=%d M=%d (%d bits, bias %d), round to nearest even, flush to zero\n",
           F24_EXP_BITS, F24_MAN_BITS, F24_WIDTH, F24_BIAS);
    printf("arithmetic path: %s\n", F24_PATH);
    printf("libraries: MPFR %s, OpenImageIO %s\n", mpfr_get_version(), img_library_version());
    return SAARCOR_EXIT_OK;
}
