/* runtime/kernels/kernel_table.cpp - the table of kernels (kernels.h) and the choice init makes from it: the
   last row whose CPU check passes, which is the widest kernel the CPU runs except on AMD Zen 4 (below). The
   checks read CPUID, so this file is built with the runtime's own flags: nothing here may need the
   instruction sets it looks for. */
#include "kernels/kernels.h"

/* Each kernel file defines its entries. */
extern const dsn_kernel_entries dsn_internal_entries_default;
#if DSN_KERNEL_X86_COPIES
extern const dsn_kernel_entries dsn_internal_entries_avx2;
extern const dsn_kernel_entries dsn_internal_entries_avx512;
extern const dsn_kernel_entries dsn_internal_entries_avx512_avx2_tiles;

#include <cpuid.h>

namespace {

/* The x86 CPU checks. A vector register file is usable only when the CPU has the instructions and the
   OS saves the registers on a context switch: CPUID leaf 1 says AVX and OSXSAVE (ECX bits 28 and 27),
   then XCR0 says which register states the OS saves. Leaf 1 must also say what GCC's -mavx2 implies and
   so lets the compiler use in both x86 kernels (the popcnt instruction among them): SSE3, SSSE3, SSE4.1,
   SSE4.2 and POPCNT (ECX bits 0, 9, 19, 20 and 23). Every CPU with AVX2 has them; a virtual CPU might
   not say so. */
int avx_usable(uint32_t xcr0_bits) {
    unsigned int eax = 0, ebx = 0, ecx = 0, edx = 0;
    const unsigned int leaf_1_bits =
        (1u << 27) | (1u << 28) | (1u << 0) | (1u << 9) | (1u << 19) | (1u << 20) | (1u << 23);
    if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx) || (ecx & leaf_1_bits) != leaf_1_bits) return 0;
    uint32_t xcr0 = 0, xcr0_high = 0;
    __asm__("xgetbv" : "=a"(xcr0), "=d"(xcr0_high) : "c"(0));
    return (xcr0 & xcr0_bits) == xcr0_bits;
}

/* CPUID leaf 7 (subleaf 0) EBX has all of `bits`. */
int leaf_7_has(uint32_t bits) {
    unsigned int eax = 0, ebx = 0, ecx = 0, edx = 0;
    if (__get_cpuid_max(0, 0) < 7) return 0;
    __cpuid_count(7, 0, eax, ebx, ecx, edx);
    return (ebx & bits) == bits;
}

/* AVX2: EBX bit 5, with the XMM and YMM state saved (XCR0 bits 1 and 2). */
int cpu_runs_avx2(void) { return leaf_7_has(1u << 5) && avx_usable(0x6u); }

/* AVX-512 F, DQ, BW and VL: EBX bits 16, 17, 30 and 31, with the opmask and ZMM state saved too (XCR0
   bits 5 to 7). AVX2 as well, which every such CPU has: the table's rows run those before them. (Every CPU
   with BW has DQ and VL; the kernel's 64-bit multiplies use them where the Makefile's flags let them.) */
int cpu_runs_avx512(void) {
    return leaf_7_has((1u << 5) | (1u << 16) | (1u << 17) | (1u << 30) | (1u << 31)) && avx_usable(0xE6u);
}

/* AMD Zen 4 (vendor AuthenticAMD, family 19h, with AVX-512) runs a 512-bit instruction as two 256-bit
   halves. Its RGB lattice tiles, bound by loads and byte widenings, are faster with the AVX2 kernel's
   strips than with AVX-512's, every output kind (a 2048 x 2048 tile of a 31 x 31 texton at 30 impacts on
   a shared EPYC: fixed 13.9-14.5 ms against 14.2-15.8, float 14.1-14.3 against 14.8-16.9, 8-bit 13.9-14.1
   against 15.1-15.7; 1024 x 1024 of a 15 x 15 texton: fixed 6.4-6.5 against 7.6-7.9, 8-bit 6.0-6.2
   against 7.2-7.5). Its grey tiles are not (fixed 8.8-9.1 ms against 7.0-7.1 at 2048 x 2048), nor those
   of RGB textons the AVX2 strips cannot hold (63 x 63: 35 ms on AVX2's 32-bit path against 3.5), nor
   the continuous point, batch, splat and filtered reads: the last row takes each from the faster. Other
   CPUs (Intel, AMD families with full-width units) keep AVX-512 throughout. */
int cpu_is_zen_4(void) {
    unsigned int eax = 0, ebx = 0, ecx = 0, edx = 0;
    if (!__get_cpuid(0, &eax, &ebx, &ecx, &edx)) return 0;
    const int amd = ebx == 0x68747541u && edx == 0x69746E65u && ecx == 0x444D4163u; /* "AuthenticAMD" */
    if (!amd || !__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return 0;
    const uint32_t base_family = (eax >> 8) & 0xFu, extended_family = (eax >> 20) & 0xFFu;
    return (base_family == 0xFu ? base_family + extended_family : base_family) == 0x19u;
}

int cpu_runs_avx512_avx2_tiles(void) { return cpu_runs_avx512() && cpu_is_zen_4(); }

} // namespace
#endif

/* Row i has id i, from the narrowest instruction set to the widest; init takes the last row whose check
   passes. */
extern const dsn_kernel dsn_internal_kernels[] = {
    {DSN_KERNEL_DEFAULT, "default", 0, &dsn_internal_entries_default},
#if DSN_KERNEL_X86_COPIES
    {DSN_KERNEL_AVX2, "AVX2", cpu_runs_avx2, &dsn_internal_entries_avx2},
    {DSN_KERNEL_AVX512, "AVX-512", cpu_runs_avx512, &dsn_internal_entries_avx512},
    {DSN_KERNEL_AVX512_AVX2_TILES, "AVX-512, AVX2 RGB lattice tiles", cpu_runs_avx512_avx2_tiles,
     &dsn_internal_entries_avx512_avx2_tiles},
#endif
};
extern const uint32_t dsn_internal_kernel_count =
    sizeof dsn_internal_kernels / sizeof dsn_internal_kernels[0];

uint32_t dsn_internal_choose_kernel(void) {
    for (uint32_t id = dsn_internal_kernel_count - 1u; id > 0; id--) {
        const dsn_kernel *kernel = &dsn_internal_kernels[id];
        if (kernel->cpu_runs == 0 || kernel->cpu_runs()) return id;
    }
    return DSN_KERNEL_DEFAULT;
}
