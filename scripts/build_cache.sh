# Sourced by scripts/build_libs and scripts/test (needs $repo): the build cache's folders
# (docs/platforms.md, "The build cache").
#   $GEOROD_CACHE (default ~/.cache/georod)/<name>-<key>: a cargo target folder, the key a hash
#   of the toolchain's version text and Cargo.lock.

cache="${GEOROD_CACHE:-$HOME/.cache/georod}"

# cache_dir NAME VERSION-TEXT: the cargo target folder of NAME for this toolchain and Cargo.lock
# (created, its time refreshed); folders of NAME's other keys unused for 14 days are removed.
cache_dir() {
    local key
    key="$( (echo "$2"; cat "$repo/Cargo.lock") | sha256sum | cut -c1-16)"
    mkdir -p "$cache"
    find "$cache" -mindepth 1 -maxdepth 1 -name "$1-*" ! -name "$1-$key*" -mtime +14 \
        -exec rm -rf {} + 2>/dev/null || true
    mkdir -p "$cache/$1-$key"
    touch "$cache/$1-$key"
    echo "$cache/$1-$key"
}

# claim DIR TAG CLEAN-COMMAND...: makes this checkout the one whose georod DIR holds (for TAG, a
# profile). Cargo judges a package fresh when its sources are older than its last build, and
# georod's artifacts are named alike in every checkout (cargo hashes paths relative to the
# workspace): after another checkout built there, this one's older sources would pass for built.
# So when the last builder was another checkout, CLEAN-COMMAND (`cargo clean -p georod ...`)
# removes georod's own artifacts first; the dependencies and the standard library stay.
claim() {
    local stamp="$1/.georod-checkout-$2"
    shift 2
    if [ "$(cat "$stamp" 2>/dev/null)" != "$repo" ]; then
        "$@"
        echo "$repo" > "$stamp"
    fi
}
