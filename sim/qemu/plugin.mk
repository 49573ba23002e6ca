# sim/qemu/plugin.mk: builds the lt_icount QEMU TCG plugin (exact instruction counts, see
# docs/qemu-plugin.md). Included by the top-level Makefile, run from the repo root; also usable
# alone: make -f sim/qemu/plugin.mk build/plugin/lt_icount.so

PLUGIN_SO     := build/plugin/lt_icount.so
PLUGIN_CC     ?= gcc
# Only qemu_plugin_version and qemu_plugin_install are exported (-fvisibility=hidden); the
# qemu_plugin_* calls stay undefined in the .so and bind to the qemu binary at dlopen time.
PLUGIN_CFLAGS ?= -std=c99 -O2 -Wall -Wextra -Wpedantic -Werror -Wshadow -Wundef \
                 -Wstrict-prototypes -Wmissing-prototypes -fPIC -fvisibility=hidden

$(PLUGIN_SO): sim/qemu/lt_icount.c sim/qemu/plugin.mk
	@mkdir -p $(dir $@)
	$(PLUGIN_CC) $(PLUGIN_CFLAGS) -shared -o $@ $<

.PHONY: plugin
plugin: $(PLUGIN_SO)
