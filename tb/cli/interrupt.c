/*
 * Records SIGINT/SIGTERM for a clean stop (see interrupt.h). The flag is a lock-free C11 atomic:
 * storing it is async-signal-safe and every render thread sees it without a lock.
 */
#define _GNU_SOURCE
#include "interrupt.h"

#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>

_Static_assert(ATOMIC_INT_LOCK_FREE == 2, "the signal flag must be lock-free to be set from a handler");

static atomic_int caught;

static void on_signal(int sig)
{
    atomic_store(&caught, sig);
}

int interrupt_catch(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND | SA_RESTART; /* a second signal: the default action (terminate) */
    if (sigaction(SIGINT, &sa, NULL) != 0 || sigaction(SIGTERM, &sa, NULL) != 0)
        return -1;
    return 0;
}

void interrupt_set(int sig)
{
    atomic_store(&caught, sig);
}

int interrupt_signal(void)
{
    return atomic_load(&caught);
}

const char *interrupt_name(int sig)
{
    return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal";
}

int interrupt_exit(const char *cmd, const char *what)
{
    const int sig = interrupt_signal();
    fprintf(stderr, "saarcor %s: interrupted by %s: %s\n", cmd, interrupt_name(sig), what);
    return 128 + sig;
}
