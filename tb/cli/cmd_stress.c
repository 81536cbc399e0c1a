/* saarcor stress: the numerical stability stress suite of this build's number format (stress.h). */
#define _GNU_SOURCE
#include <getopt.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "f24.h"
#include "interrupt.h"
#include "stress.h"

enum { MAX_CASES = 64 };

static void print_table(const stress_result *r, int n)
{
    printf("%-14s %7s %7s %7s %8s %6s %6s %6s %4s %4s %9s %9s %4s %s\n", "case", "rays", "units", "ref", "agree%", "leaks",
           "multi", "acne", "trav", "bad", "p99 t err", "max t err", "drop", "pass");
    for (int i = 0; i < n; i++) {
        if (r[i].build_failed) {
            printf("%-14s %s %s\n", r[i].name, "(scene refused by the host)", r[i].pass ? "PASS" : "FAIL");
            continue;
        }
        printf("%-14s %7llu %7llu %7llu %8.3f %6llu %6llu %6llu %4llu %4llu %9.2e %9.2e %4u %s\n", r[i].name,
               (unsigned long long)r[i].rays, (unsigned long long)r[i].unit_hits, (unsigned long long)r[i].ref_hits,
               r[i].rays ? 100.0 * (double)r[i].agree / (double)r[i].rays : 0.0, (unsigned long long)r[i].leaks,
               (unsigned long long)r[i].multi, (unsigned long long)r[i].acne, (unsigned long long)r[i].traversal,
               (unsigned long long)r[i].bad, r[i].t_err_p99, r[i].t_err_max, r[i].dropped, r[i].pass ? "PASS" : "FAIL");
    }
}

static int write_json(const char *path, const stress_result *r, int n)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fprintf(f, "[\n");
    for (int i = 0; i < n; i++)
        fprintf(f,
                "  {\"format\": \"e%dm%d\", \"case\": \"%s\", \"what\": \"%s\", \"criterion\": \"%s\", \"rays\": %llu, "
                "\"units_hits\": %llu, \"ref_hits\": %llu, \"agree\": %llu, \"leaks\": %llu, \"multi\": %llu, "
                "\"acne\": %llu, \"traversal\": %llu, \"bad\": %llu, \"nondeterministic\": %llu, \"dropped\": %u, \"refused\": %d, "
                "\"t_err_p99\": %.6g, \"t_err_max\": %.6g, \"pass\": %s}%s\n",
                F24_EXP_BITS, F24_MAN_BITS, r[i].name, r[i].what, r[i].criterion, (unsigned long long)r[i].rays,
                (unsigned long long)r[i].unit_hits, (unsigned long long)r[i].ref_hits, (unsigned long long)r[i].agree,
                (unsigned long long)r[i].leaks, (unsigned long long)r[i].multi, (unsigned long long)r[i].acne,
                (unsigned long long)r[i].traversal, (unsigned long long)r[i].bad, (unsigned long long)r[i].nondeterministic, r[i].dropped,
                r[i].build_failed, r[i].t_err_p99, r[i].t_err_max, r[i].pass ? "true" : "false", i + 1 < n ? "," : "");
    fprintf(f, "]\n");
    return fclose(f);
}

int cmd_stress(int argc, char **argv)
{
    static const struct option opts[] = {
        { "rays", required_argument, NULL, 'n' }, { "case", required_argument, NULL, 'c' },
        { "json", required_argument, NULL, 'j' }, { "shared", required_argument, NULL, 's' },
        { "check", no_argument, NULL, 'k' },      { "list", no_argument, NULL, 'l' },
        { "help", no_argument, NULL, 'h' },       { 0, 0, 0, 0 }
    };
    uint64_t rays = 20000;
    const char *filter = NULL, *json = NULL, *shared = "../shared/scenes";
    int check = 0, list = 0, c;
    optind = 0;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "n:c:j:s:klh", opts, NULL)) != -1) {
        switch (c) {
        case 'n':
            if (!cli_parse_u64(optarg, 4, 10000000, &rays))
                return cli_usage_error("stress", "bad --rays '%s' (4 .. 10^7)", optarg);
            break;
        case 'c': filter = optarg; break;
        case 'j': json = optarg; break;
        case 's': shared = optarg; break;
        case 'k': check = 1; break;
        case 'l': list = 1; break;
        case 'h':
            printf("usage: saarcor stress [--rays N] [--case TEXT] [--json FILE] [--check] [--shared DIR] [--list]\n\n"
                   "The numerical stability stress suite (docs/stress.md) in this build's number format\n"
                   "(e%dm%d): adversarial scenes (closed meshes hit at their edges and vertices, geometry\n"
                   "far from the origin, tiny and huge scales, slivers, extreme instance matrices, rays in\n"
                   "split and face planes, grazing and surface-starting rays, NaN/Inf inputs), each ray\n"
                   "traced by the units and by the binary64 reference on the same fp24 ray. Columns: hits\n"
                   "of units and reference, hit agreement, leaks (rays that pass through a surface they\n"
                   "were aimed at), multi (rays two triangles accept), acne (rays leaving a convex surface\n"
                   "that hit it), trav (closest hits that differ from brute force), bad (non-finite or out-of-range hits), relative t error, triangles the\n"
                   "host dropped, and the case's criterion.\n"
                   "  --rays N      rays per case (default 20000)\n"
                   "  --case LIST   only the cases whose name contains one of the comma-separated texts\n"
                   "  --json FILE   the rows as JSON\n"
                   "  --check       exit 1 if a case fails its criterion\n"
                   "  --shared DIR  folder of the shared scenes (default ../shared/scenes; cases that need\n"
                   "                one are skipped if it is missing)\n"
                   "  --list        list the cases and their criteria\n",
                   F24_EXP_BITS, F24_MAN_BITS);
            return SAARCOR_EXIT_OK;
        default: return cli_bad_option("stress", argc, argv);
        }
    }
    if (optind != argc)
        return cli_usage_error("stress", "unexpected argument '%s'", argv[optind]);
    if (cli_parse_only)
        return SAARCOR_EXIT_OK;
    static stress_result r[MAX_CASES];
    if (list) {
        const int n = stress_describe(r, MAX_CASES);
        for (int i = 0; i < n; i++)
            printf("%-14s %s\n%-14s criterion: %s\n", r[i].name, r[i].what, "", r[i].criterion);
        return SAARCOR_EXIT_OK;
    }
    if (interrupt_catch() != 0)
        cli_error("stress", "cannot catch SIGINT/SIGTERM: Ctrl-C will not stop cleanly");
    const int n = stress_run(filter, (uint32_t)rays, shared, r, MAX_CASES);
    if (interrupt_signal())
        return interrupt_exit("stress", "nothing written");
    if (n < 0) {
        cli_error("stress", "out of memory");
        return SAARCOR_EXIT_INTERNAL;
    }
    if (n == 0)
        return cli_usage_error("stress", "no case matches '%s'", filter ? filter : "");
    printf("stress suite, format e%dm%d, %llu rays per case\n", F24_EXP_BITS, F24_MAN_BITS, (unsigned long long)rays);
    print_table(r, n);
    int failed = 0;
    for (int i = 0; i < n; i++)
        failed += !r[i].pass;
    printf("%d of %d cases pass their criteria\n", n - failed, n);
    if (json && write_json(json, r, n) != 0) {
        cli_error("stress", "cannot write %s", json);
        return SAARCOR_EXIT_INPUT;
    }
    return check && failed ? SAARCOR_EXIT_FAIL : SAARCOR_EXIT_OK;
}
