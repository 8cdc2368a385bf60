# Dynamics Lab, production image: slim Python, pinned requirements, non-root, health-checked,
# and nothing fetched from the internet at run time.
ARG BASE_IMAGE=python:3.11-slim
FROM ${BASE_IMAGE}

# Optional, build time only: a CA bundle for a TLS-intercepting proxy in front of PyPI
# (e.g. --build-arg PIP_CERT=/etc/ssl/host-ca.crt with that file mounted). Empty by default.
ARG PIP_CERT=""

ENV PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1 \
    PIP_NO_CACHE_DIR=1 \
    PIP_DISABLE_PIP_VERSION_CHECK=1 \
    VIRTUAL_ENV=/opt/venv \
    PATH=/opt/venv/bin:$PATH

WORKDIR /app
COPY requirements.txt .
RUN python3 -m venv /opt/venv \
 && if [ -n "$PIP_CERT" ]; then export PIP_CERT; else unset PIP_CERT; fi \
 && pip install -r requirements.txt \
 && useradd --create-home --uid 10001 --shell /usr/sbin/nologin app \
 && mkdir /data && chown app:app /data

COPY --chown=app:app . .
USER app

# Assignments' records: a SQLite file on this volume unless DL_DATABASE_URL names a PostgreSQL server
# (which several replicas must share). serve.py brings the schema up to date before it listens.
ENV DL_DATA_DIR=/data
VOLUME ["/data"]

EXPOSE 8501
HEALTHCHECK --interval=15s --timeout=5s --start-period=60s --retries=3 \
  CMD ["python3", "-c", "import sys, urllib.request as u; sys.exit(0 if u.urlopen('http://127.0.0.1:8501/_stcore/health', timeout=4).read().strip() == b'ok' else 1)"]

# Offline-safe: no welcome banner (its headless "External URL" line looks the IP up on the
# internet), no telemetry; set STREAMLIT_BROWSER_SERVER_ADDRESS to the public host name so that a
# cross-origin websocket never triggers that lookup either (see README, Deploy).
ENV STREAMLIT_LOGGER_HIDE_WELCOME_MESSAGE=true \
    STREAMLIT_BROWSER_GATHER_USAGE_STATS=false \
    STREAMLIT_SERVER_HEADLESS=true \
    STREAMLIT_SERVER_FILE_WATCHER_TYPE=none

# serve.py derives every problem before the server listens: healthy means warm.
CMD ["python3", "serve.py", "--server.port=8501", "--server.address=0.0.0.0"]
