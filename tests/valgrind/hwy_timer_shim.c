/*
 * LD_PRELOAD shim for the valgrind memcheck pass (tests/test_memcheck.sh), used only on hosts
 * whose CPU lacks RDTSCP. Why: OpenImageIO links libjxl, which links Highway (libhwy); libhwy's
 * static initializer calls hwy::platform::TimerResolution(), which executes RDTSCP when CPUID
 * says the CPU has it. Valgrind 3.19's emulated CPUID (the AVX2 model) always says so, but its
 * decoder accepts RDTSCP only if the real CPU has it: on such a virtual machine every program
 * linking OpenImageIO dies with SIGILL under valgrind before main. The call goes through libhwy's
 * PLT, so this definition replaces it. The value is only a timer resolution in ticks, which
 * nothing in saarcor reads; none of our code is replaced.
 */
double _ZN3hwy8platform15TimerResolutionEv(void);

double _ZN3hwy8platform15TimerResolutionEv(void)
{
    return 1.0;
}
