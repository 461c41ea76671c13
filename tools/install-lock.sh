# Sourced by the install scripts: one install at a time on this machine, whoever
# calls (parallel tests, several test binaries, .ci/run). What a script checks after
# sourcing this, it checks inside the lock, so a caller that waited finds the work
# done. A script called by one holding the lock (install-peers.sh calling
# apt-install.sh) does not take it again.
if [ -z "${LUMIERE_INSTALL_LOCKED:-}" ]; then
    export LUMIERE_INSTALL_LOCKED=1
    exec 9>"${TMPDIR:-/tmp}/lumiere-install.lock"
    flock 9
fi
