# Sourced by scripts/test --sanitize and scripts/fuzz: the one sanitized build tree they share,
# and the sanitizer settings both run under. Not executable on its own.
#
# The tree ($PINMASK_SAN_BUILD_DIR, default build-san/) is clang, RelWithDebInfo, AddressSanitizer
# + UndefinedBehaviorSanitizer (PINMASK_SANITIZE=ON: -fno-sanitize-recover=all) and the libFuzzer
# targets (PINMASK_FUZZ=ON: the libraries carry coverage instrumentation, which the tests do not
# notice). One tree for both saves CI a full build on its 2 cores.

san_build_dir=${PINMASK_SAN_BUILD_DIR:-build-san}

# sanitized_build [target...]: configures the tree and builds the targets (default: all).
sanitized_build() {
    local launcher=()
    command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
    # Paths relative to the checkout, so a clone elsewhere reuses what an earlier tree compiled.
    export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
    # Ninja for a new tree when it is installed (as scripts/build): it compiles a library's
    # sources while the libraries it depends on still link.
    local generator=()
    if command -v ninja >/dev/null; then
        if [[ ! -f $san_build_dir/CMakeCache.txt ]] ||
            grep -qx 'CMAKE_GENERATOR:INTERNAL=Ninja' "$san_build_dir/CMakeCache.txt"; then
            generator=(-G Ninja)
        fi
    fi
    CC=clang CXX=clang++ cmake -S . -B "$san_build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DPINMASK_SANITIZE=ON -DPINMASK_FUZZ=ON "${generator[@]}" "${launcher[@]}" >/dev/null
    local targets=()
    (($#)) && targets=(--target "$@")
    cmake --build "$san_build_dir" -j "$(nproc)" "${targets[@]}"
}

# The first report of any sanitizer ends the process with exit code 86, a code pinmask never
# uses: the CLI tests expect exactly 0, 1 or 2, so a report inside a `pinmask` run they start
# fails them too (the sanitizers' default, 1, is also `check`'s "violations found"). Leak
# checking is on, with scripts/lsan.supp for fontconfig's process-lifetime caches.
export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:exitcode=86:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:exitcode=86:print_stacktrace=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-exitcode=86:suppressions=$PWD/scripts/lsan.supp:print_suppressions=0}
