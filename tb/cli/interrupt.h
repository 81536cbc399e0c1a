/*
 * Ctrl-C and SIGTERM for long renders. interrupt_catch installs handlers that only record the
 * signal (an async-signal-safe store); the render loops poll interrupt_signal() at safe points
 * (between block rows, between cycle-model epochs, between frames), stop their host threads
 * there, keep the frames already written and exit with 128 + the signal number. The handlers
 * reset themselves (SA_RESETHAND): a second Ctrl-C kills the program at once, the usual escape
 * when something does not stop.
 */
#ifndef SAARCOR_INTERRUPT_H
#define SAARCOR_INTERRUPT_H

/* Installs the handlers for SIGINT and SIGTERM; 0, or -1 if sigaction failed. */
int interrupt_catch(void);

/* The signal caught so far (SIGINT or SIGTERM), 0 if none. Safe from any thread. */
int interrupt_signal(void);

/* "SIGINT" or "SIGTERM" for a caught signal. */
const char *interrupt_name(int sig);

/* Sets the caught signal to sig, 0 forgets it. For the command-line fuzzer (tests/fuzz/fuzz_cli.c),
 * which runs many commands in one process, each with a time bound that stops it as Ctrl-C would. */
void interrupt_set(int sig);

/* For a command stopped by the caught signal that keeps no output: prints
 * "saarcor CMD: interrupted by SIGINT: <what>" on stderr and returns its exit code, 128 + the signal. */
int interrupt_exit(const char *cmd, const char *what);

#endif
