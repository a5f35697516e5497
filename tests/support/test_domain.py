"""Per-test DDS domain ids for the Python tests, shared with the C++ tests (test_domain.cpp) and
the C tests: an exclusive flock on /tmp/robotd-test-domain-<id>.lock, held while the test runs."""
import fcntl

FIRST_DOMAIN_ID, LAST_DOMAIN_ID = 100, 229


def claim_domain_id(taken=()):
    """Locks the first free test domain id not in `taken`; returns (id, open lock file), whose
    closing releases it. Raises if every id is locked."""
    for domain_id in range(FIRST_DOMAIN_ID, LAST_DOMAIN_ID + 1):
        if domain_id in taken:
            continue
        lock = open(f"/tmp/robotd-test-domain-{domain_id}.lock", "w")
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return domain_id, lock
        except BlockingIOError:
            lock.close()
    raise RuntimeError(f"every DDS domain id in {FIRST_DOMAIN_ID}..{LAST_DOMAIN_ID} is locked by another test")
