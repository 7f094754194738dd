/* mcu_startup.c - bare-metal start of the golden program on a Cortex-M (QEMU mps2-an385): vector table,
   .data/.bss set-up, main(), then exit through ARM semihosting with main's status. golden_write() prints
   through semihosting too, so no C library I/O is linked. */
#include <stdint.h>

#include "golden_output.h"

/* Defined by mcu.ld. */
extern uint32_t __stack_top, __data_load, __data_start, __data_end, __bss_start, __bss_end;

int main(void);

enum {
    semihosting_write0 = 0x04,        /* SYS_WRITE0: print a NUL-terminated string */
    semihosting_exit_extended = 0x20, /* SYS_EXIT_EXTENDED: stop with a reason and a status */
    semihosting_application_exit = 0x20026
};

static uint32_t semihosting_call(uint32_t operation, const void *argument) {
    register uint32_t r0 __asm__("r0") = operation;
    register const void *r1 __asm__("r1") = argument;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void golden_write(const char *text) { semihosting_call(semihosting_write0, text); }

static void semihosting_exit(int status) {
    const uint32_t block[2] = {semihosting_application_exit, (uint32_t)status};
    semihosting_call(semihosting_exit_extended, block);
    for (;;) {
    }
}

void reset_handler(void) {
    const uint32_t *source = &__data_load;
    uint32_t *word;
    for (word = &__data_start; word < &__data_end;) *word++ = *source++;
    for (word = &__bss_start; word < &__bss_end;) *word++ = 0;
    semihosting_exit(main());
}

/* Any fault ends the run with a distinct status instead of hanging until the timeout. */
static void fault_handler(void) {
    golden_write("fault\n");
    semihosting_exit(3);
}

typedef void (*vector)(void);

__attribute__((section(".vectors"), used)) static const vector vector_table[16] = {
    (vector)&__stack_top, /* initial stack pointer */
    reset_handler,        /* reset */
    fault_handler,        /* NMI */
    fault_handler,        /* HardFault */
    fault_handler,        /* MemManage */
    fault_handler,        /* BusFault */
    fault_handler,        /* UsageFault */
    0,                    /* reserved */
    0,                    /* reserved */
    0,                    /* reserved */
    0,                    /* reserved */
    fault_handler,        /* SVCall */
    fault_handler,        /* DebugMonitor */
    0,                    /* reserved */
    fault_handler,        /* PendSV */
    fault_handler,        /* SysTick */
};
