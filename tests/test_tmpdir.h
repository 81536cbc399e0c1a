/* A scratch directory for a cmocka test group: created by the group setup, removed by teardown. */
#ifndef SAARCOR_TEST_TMPDIR_H
#define SAARCOR_TEST_TMPDIR_H

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static char test_dir[64];

static int test_tmpdir_setup(void **state)
{
    (void)state;
    snprintf(test_dir, sizeof test_dir, "/tmp/saarcor-test-XXXXXX");
    return mkdtemp(test_dir) ? 0 : -1;
}

static int test_tmpdir_teardown(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", test_dir);
    return system(cmd) == 0 ? 0 : -1;
}

#endif
