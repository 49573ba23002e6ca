/* start.S - RV32 start-up for QEMU virt (-bios none, machine mode): gp, sp, trap vector, a locked
 * PMP guard page below the stack, .data copy (a no-op when loaded in place), .bss zero, then
 * main and lt_fw_exit(main's return). Traps switch to their own small stack (an overflowed stack
 * must not be used to report itself) and go to lt__fw_trap_report in platform.c.
 * Builds: firmware, rv32 (riscv64-unknown-elf-gcc -march=rv32imac -mabi=ilp32; CSR access needs
 * Zicsr, enabled locally with .option arch so the rv32imac multilib stays selected).
 */
    .section .text.init, "ax", @progbits
    .globl lt__fw_start
    .type lt__fw_start, @function
lt__fw_start:
    /* gp must be loaded without relaxation, or the linker would rewrite it relative to itself. */
    .option push
    .option norelax
    la      gp, __global_pointer$
    .option pop

    .option push
    .option arch, +zicsr
    csrr    t0, mhartid
    bnez    t0, 2f                      /* only hart 0 runs the program */

    la      t0, lt__fw_trap_entry
    csrw    mtvec, t0                   /* direct mode: the address is 4-byte aligned */

    /* PMP entry 0: NAPOT, 4 KiB at lt__fw_stack_guard, no R/W/X, locked (L applies it to
     * M-mode too). pmpaddr = (base >> 2) | (size / 8 - 1). Other M-mode accesses match no
     * entry and are allowed. */
    la      t0, lt__fw_stack_guard
    srli    t0, t0, 2
    ori     t0, t0, 0x1FF
    csrw    pmpaddr0, t0
    li      t0, 0x98                    /* L (0x80) | A = NAPOT (0x18) */
    csrw    pmpcfg0, t0
    .option pop

    la      sp, lt__fw_stack_top

    la      a0, lt__fw_data_start
    la      a1, lt__fw_data_load
    la      a2, lt__fw_data_end
    sub     a2, a2, a0
    beq     a0, a1, 1f
    call    lt__memcpy
1:
    la      a0, lt__fw_bss_start
    li      a1, 0
    la      a2, lt__fw_bss_end
    sub     a2, a2, a0
    call    lt__memset
    call    lt__fw_stack_paint

    call    lt__fw_uart_init
    call    lt__fw_ticks_init
    call    main
    tail    lt_fw_exit                  /* a0 = main's return value */

2:  wfi                                 /* parked harts */
    j       2b
    .size lt__fw_start, . - lt__fw_start

    .align 2
    .globl lt__fw_trap_entry
    .type lt__fw_trap_entry, @function
lt__fw_trap_entry:
    mv      a3, sp                      /* the faulting sp, reported */
    la      sp, lt__fw_trap_stack_top
    .option push
    .option arch, +zicsr
    csrr    a0, mcause
    csrr    a1, mepc
    csrr    a2, mtval
    .option pop
    tail    lt__fw_trap_report
    .size lt__fw_trap_entry, . - lt__fw_trap_entry
