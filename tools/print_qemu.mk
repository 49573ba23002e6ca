# print_qemu.mk - print the QEMU command variables of targets.mk as shell assignments.
include firmware/targets/targets.mk
all:
	@$(foreach t,$(FW_TARGETS),echo 'QEMU_$(t)="$(QEMU_$(t))"';)
