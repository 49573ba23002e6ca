# targets.mk - bare-metal firmware targets for QEMU (included by the top-level Makefile; paths are
# relative to the repository root). For each T in $(FW_TARGETS):
#   CC_T          compiler driver
#   CFLAGS_T      architecture flags, include paths and target defines (LT_FW_TARGET_NAME,
#                 LT_FW_UART_BASE, LT_FW_SYSTICK_HZ); add $(FW_CFLAGS_COMMON) for warnings/-O2
#   LDFLAGS_T     architecture flags again (they pick the libgcc multilib), linker script,
#                 -nostdlib -nostartfiles --gc-sections
#   LDLIBS_T      -lgcc; goes after the objects
#   FW_RT_SRCS_T  runtime sources (.c and .S) every image of T links
#   QEMU_T        QEMU command prefix; append the ELF path. stdout = UART, exit status = exit code
# Link: $(CC_T) $(LDFLAGS_T) -o x.elf <objects> $(LDLIBS_T). See docs/firmware.md.

FW_TARGETS := cm4 cm55 rv32

FW_TGT_DIR := firmware/targets
FW_INC := -Ifirmware/include -I$(FW_TGT_DIR)/common

# Warning and code-generation flags shared by all firmware (the project's strict C99 set).
# optimisation of every firmware image: -O2 (the default; the machine models are calibrated on it)
# or, for example, make firmware FW_OPT=-O3 (measured in docs/firmware.md: fewer instructions per
# packet ray, ~110 KB more code)
FW_OPT ?= -O2
FW_CFLAGS_COMMON ?= -std=c99 -Wall -Wextra -Wpedantic -Werror -Wshadow -Wundef -Wstrict-prototypes \
    -Wmissing-prototypes -Wcast-align -Wconversion -ffreestanding -fno-builtin \
    -ffunction-sections -fdata-sections $(FW_OPT) -g

FW_LDFLAGS_COMMON := -nostdlib -nostartfiles -Wl,--gc-sections

FW_RT_COMMON := $(FW_TGT_DIR)/common/lt_rt.c
FW_RT_CM := $(FW_RT_COMMON) $(FW_TGT_DIR)/cortex-m/startup.c $(FW_TGT_DIR)/cortex-m/semihost.c \
    $(FW_TGT_DIR)/cortex-m/uart_cmsdk.c $(FW_TGT_DIR)/cortex-m/ticks.c

FW_QEMU_ARM := qemu-system-arm -nographic -monitor none -serial stdio \
    -semihosting-config enable=on,target=native -icount shift=0

# cm4: Cortex-M4F on mps2-an386. SysTick runs on the 25 MHz board clock.
ARCH_cm4 := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16
CC_cm4 := arm-none-eabi-gcc
CFLAGS_cm4 := $(ARCH_cm4) -DLT_FW_TARGET_NAME=\"cm4\" \
    -DLT_FW_UART_BASE=0x40004000u -DLT_FW_SYSTICK_HZ=25000000
LDFLAGS_cm4 := $(ARCH_cm4) -T $(FW_TGT_DIR)/cortex-m/mps2_an386.ld $(FW_LDFLAGS_COMMON)
LDLIBS_cm4 := -lgcc
FW_RT_SRCS_cm4 := $(FW_RT_CM)
QEMU_cm4 := $(FW_QEMU_ARM) -M mps2-an386 -kernel

# cm55: Cortex-M55 + MVE on mps3-an547 (secure state). SysTick runs on the 32 MHz board clock.
ARCH_cm55 := -mcpu=cortex-m55 -mthumb -mfloat-abi=hard
CC_cm55 := arm-none-eabi-gcc
CFLAGS_cm55 := $(ARCH_cm55) -DLT_FW_TARGET_NAME=\"cm55\" \
    -DLT_FW_UART_BASE=0x49303000u -DLT_FW_SYSTICK_HZ=32000000
LDFLAGS_cm55 := $(ARCH_cm55) -T $(FW_TGT_DIR)/cortex-m/mps3_an547.ld $(FW_LDFLAGS_COMMON)
LDLIBS_cm55 := -lgcc
FW_RT_SRCS_cm55 := $(FW_RT_CM)
QEMU_cm55 := $(FW_QEMU_ARM) -M mps3-an547 -kernel

# rv32: RV32IMAC on virt, machine mode, no firmware (-bios none). Keep -march=rv32imac: adding
# _zicsr selects the rv64 default multilib of this toolchain (CSR code uses .option arch instead).
ARCH_rv32 := -march=rv32imac -mabi=ilp32 -mcmodel=medany
CC_rv32 := riscv64-unknown-elf-gcc
CFLAGS_rv32 := $(ARCH_rv32) -DLT_FW_TARGET_NAME=\"rv32\" -DLT_FW_UART_BASE=0x10000000u
LDFLAGS_rv32 := $(ARCH_rv32) -T $(FW_TGT_DIR)/riscv/virt_rv32.ld $(FW_LDFLAGS_COMMON)
LDLIBS_rv32 := -lgcc
FW_RT_SRCS_rv32 := $(FW_RT_COMMON) $(FW_TGT_DIR)/riscv/start.S $(FW_TGT_DIR)/riscv/platform.c
QEMU_rv32 := qemu-system-riscv32 -M virt -bios none -nographic -monitor none -serial stdio \
    -semihosting-config enable=on,target=native -icount shift=0 -kernel

# Everything a firmware image depends on besides its own sources (for prerequisites).
FW_RT_DEPS := $(FW_TGT_DIR)/targets.mk $(FW_TGT_DIR)/common/lt_fw.h firmware/include/lt/lt_port.h \
    $(FW_TGT_DIR)/cortex-m/mps2_an386.ld $(FW_TGT_DIR)/cortex-m/mps3_an547.ld \
    $(FW_TGT_DIR)/riscv/virt_rv32.ld
