# layout.sh - the rooms' rules (tools/check_layout.sh, `make layout`): the tree passes, and a
# sandbox tree that breaks each rule (a core file including a host header, a tests/ fragment
# defining a shipped program, a host file including a test header, a sim file including a host
# header other than io/lt_diag.h) fails with the file named.
# Sourced by tests/run_tests.sh ($B, $tmp, check/ok/ko).
tools/check_layout.sh >"$tmp/layout.txt" 2>&1
rc=$?
check "make layout: the tree keeps the rooms' rules (rc $rc; $(grep -c '^layout:' "$tmp/layout.txt") rules)" \
    test "$rc" -eq 0
lsb="$tmp/layout-sandbox"
mkdir -p "$lsb/tools" "$lsb/firmware/core/object" "$lsb/firmware/include/lt" "$lsb/firmware/apps" \
    "$lsb/host/io" "$lsb/host/cli" "$lsb/sim" "$lsb/tests/unit"
cp tools/check_layout.sh "$lsb/tools/"
printf '#include <stdint.h>\n#include "lt/lt.h"\n#include "io/lt_exr.h"\n' >"$lsb/firmware/core/object/a.c"
printf '#include <stdio.h>\n' >"$lsb/firmware/core/object/b.c"
printf '/* api */\n' >"$lsb/firmware/include/lt/lt.h"
printf '/* exr */\n' >"$lsb/host/io/lt_exr.h"
printf '#include "lt_test_util.h"\n' >"$lsb/host/cli/m.c"
printf '#include "io/lt_diag.h"\n#include "io/lt_exr.h"\n' >"$lsb/sim/s.c"
printf '/* diag */\n' >"$lsb/host/io/lt_diag.h"
printf '/* util */\n' >"$lsb/tests/unit/lt_test_util.h"
printf 'print-product-deps:\n\t@echo "lanetrace: build/sim/obj/tests/x.o build/sim/obj/host/cli/m.o"\n' >"$lsb/Makefile"
printf '$(B)/sim/lanetrace: x.o\n' >"$lsb/tests/bad.mk"
(cd "$lsb" && git init -q && git add -A) >/dev/null 2>&1
(cd "$lsb" && tools/check_layout.sh) >"$tmp/layout-bad.txt" 2>&1
rc=$?
check "make layout fails on a broken sandbox tree (rc $rc)" test "$rc" -eq 1
check "layout names the core file that includes a host header" \
    grep -q 'firmware/core/object/a.c: #include "io/lt_exr.h" resolves nowhere' "$tmp/layout-bad.txt"
check "layout names the core file that includes a hosted system header" \
    grep -q 'firmware/core/object/b.c: #include <stdio.h> is not allowed' "$tmp/layout-bad.txt"
check "layout names the host file that includes a test header" \
    grep -q 'host/cli/m.c: #include "lt_test_util.h"' "$tmp/layout-bad.txt"
check "layout names the sim file that includes a host header other than io/lt_diag.h" \
    grep -q 'sim/s.c: #include "io/lt_exr.h" is host/io/lt_exr.h, outside sim' "$tmp/layout-bad.txt"
check "layout lets sim/ include io/lt_diag.h" \
    bash -c "! grep -q 'sim/s.c: #include \"io/lt_diag.h\"' '$tmp/layout-bad.txt'"
check "layout names a shipped program linking an object from tests/" \
    grep -q 'shipped programs link objects built from tests/: build/sim/obj/tests/x.o' "$tmp/layout-bad.txt"
check "layout names a tests/ fragment defining a shipped program" \
    grep -q 'tests/bad.mk defines the shipped program lanetrace' "$tmp/layout-bad.txt"
