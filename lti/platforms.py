"""The LMS platforms the admin registered, the tool's own signing key, and the tool's public URL.

Platforms are listed in a JSON file named by ``DL_LTI_PLATFORMS`` (several platforms, each with
several deployments); LTI is off when it is unset. One entry per registration (issuer + client id):

    [{"issuer": "https://canvas.instructure.com", "client_id": "10000000000001",
      "auth_login_url": "https://sso.canvaslms.com/api/lti/authorize_redirect",
      "auth_token_url": "https://sso.canvaslms.com/login/oauth2/token",
      "key_set_url": "https://sso.canvaslms.com/api/lti/security/jwks",
      "deployment_ids": ["1:8865aa05b4b79b64a91a86042e43af5ea8ae79eb"],
      "frame_origins": ["https://canvas.example.edu"]}]

``frame_origins`` are the origins whose pages embed the tool (the school's LMS address; the
issuer's origin when left out): they join ``DL_FRAME_ANCESTORS`` in the Content-Security-Policy.
The tool signs its own messages (deep-linking answers, AGS token requests) with the RSA key in
``DL_LTI_KEY_FILE``, or with one it makes once in the data directory. ``DL_PUBLIC_URL`` is the
address students use (https://dynamics.example.edu): the URLs the platform is given start with it.
"""
from __future__ import annotations

import functools
import json
import os
import re
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import urlsplit

PLATFORMS_ENV, KEY_ENV, URL_ENV, NAMES_ENV = "DL_LTI_PLATFORMS", "DL_LTI_KEY_FILE", "DL_PUBLIC_URL", "DL_LTI_KEEP_NAMES"
FIELDS = ("issuer", "client_id", "auth_login_url", "auth_token_url", "key_set_url", "deployment_ids")
_URL = re.compile(r"^https?://[A-Za-z0-9.-]+(:\d{1,5})?(/[^\s]*)?$")


class NotRegistered(ValueError):
    """The platform file cannot be used as it is (the message says what to mend)."""


@dataclass(frozen=True)
class Platform:
    issuer: str
    client_id: str
    auth_login_url: str
    auth_token_url: str
    key_set_url: str
    deployment_ids: tuple[str, ...]
    frame_origins: tuple[str, ...]


def owns(platform: Platform, url: object) -> bool:
    """``url`` is an http(s) address on one of the platform's own origins (its issuer, login, token,
    key set and frame origins): where the tool sends a score, a bearer token or a signed answer.
    The LTI specs do not name the hosts of a service URL; the tool refuses others rather than be
    told by a launch to post tokens or students' scores to any address (a server-side request
    forgery, a ``javascript:`` URL)."""
    if not isinstance(url, str) or not _URL.match(url):
        return False
    known = {origin(u) for u in (platform.issuer, platform.auth_login_url, platform.auth_token_url,
                                 platform.key_set_url)} | set(platform.frame_origins)
    return origin(url).lower() in {k.lower() for k in known}


def enabled() -> bool:
    return bool(os.environ.get(PLATFORMS_ENV, "").strip())


def keep_names() -> bool:
    return os.environ.get(NAMES_ENV, "") == "1"


def origin(url: str) -> str:
    parts = urlsplit(url)
    return f"{parts.scheme}://{parts.netloc}"


def _platform(entry: object, where: str) -> Platform:
    if not isinstance(entry, dict):
        raise NotRegistered(f"{where} is not an object with {', '.join(FIELDS)}")
    missing = [f for f in FIELDS if not entry.get(f)]
    if missing:
        raise NotRegistered(f"{where} lacks {', '.join(missing)}")
    for name in ("issuer", "auth_login_url", "auth_token_url", "key_set_url"):
        if not isinstance(entry[name], str) or not _URL.match(entry[name]):
            raise NotRegistered(f"{where}: {name} {entry[name]!r} is not an http(s) URL")
    deployments, frames = entry["deployment_ids"], entry.get("frame_origins") or [origin(entry["issuer"])]
    if not (isinstance(deployments, list) and all(isinstance(d, str) and d for d in deployments)):
        raise NotRegistered(f"{where}: deployment_ids must be a list of the platform's deployment ids")
    if not (isinstance(frames, list) and all(isinstance(f, str) and _URL.match(f) and f == origin(f) for f in frames)):
        raise NotRegistered(f"{where}: frame_origins must be a list of origins such as https://lms.example.edu")
    return Platform(entry["issuer"], str(entry["client_id"]), entry["auth_login_url"], entry["auth_token_url"],
                    entry["key_set_url"], tuple(deployments), tuple(frames))


@functools.cache
def _read(path: str) -> tuple[Platform, ...]:
    try:
        entries = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as error:
        raise NotRegistered(f"{PLATFORMS_ENV}: cannot read {path} ({error.strerror})") from None
    except ValueError as error:
        raise NotRegistered(f"{PLATFORMS_ENV}: {path} is not valid JSON ({error})") from None
    if not isinstance(entries, list) or not entries:
        raise NotRegistered(f"{PLATFORMS_ENV}: {path} must hold a list of platforms")
    found = tuple(_platform(e, f"{PLATFORMS_ENV}: platform {i + 1} in {path}") for i, e in enumerate(entries))
    keys = [(p.issuer, p.client_id) for p in found]
    if len(set(keys)) != len(keys):
        raise NotRegistered(f"{PLATFORMS_ENV}: {path} registers one issuer and client id twice")
    return found


def platforms() -> tuple[Platform, ...]:
    path = os.environ.get(PLATFORMS_ENV, "").strip()
    return _read(path) if path else ()


def find(issuer: object, client_id: object = None) -> Platform | None:
    """The registration for this issuer (and client id, where the platform named one)."""
    matches = [p for p in platforms() if p.issuer == issuer and (client_id in (None, "") or p.client_id == client_id)]
    return matches[0] if len(matches) == 1 else None


def serving(issuer: str, deployment: str) -> Platform | None:
    """The registration of this issuer that has this deployment (hosted Canvas: one issuer, many
    registrations, told apart by their deployments)."""
    matches = [p for p in platforms() if p.issuer == issuer and deployment in p.deployment_ids]
    return matches[0] if len(matches) == 1 else None


def frame_origins() -> tuple[str, ...]:
    return tuple(dict.fromkeys(o for p in platforms() for o in p.frame_origins))


def public_url() -> str:
    return os.environ.get(URL_ENV, "").strip().rstrip("/")


def problems() -> list[str]:
    """What in the LTI settings cannot work (serve.py refuses to start on any)."""
    if not enabled():
        return []
    try:
        platforms()
    except NotRegistered as error:
        return [str(error)]
    if not _URL.match(public_url()):
        return [f"{PLATFORMS_ENV} is set (LTI is on) but {URL_ENV} is not the app's public address, such as "
                "https://dynamics.example.edu: the platform needs it to reach the tool."]
    try:
        tool_key()
    except (OSError, ValueError) as error:
        return [f"{KEY_ENV}: the tool's key cannot be read ({error})."]
    return []


@functools.cache
def _tool_key(path: str):
    from cryptography.hazmat.primitives import serialization
    from cryptography.hazmat.primitives.asymmetric import rsa

    file = Path(path)
    if not file.exists() and not os.environ.get(KEY_ENV):
        file.parent.mkdir(parents=True, exist_ok=True)
        made = rsa.generate_private_key(public_exponent=65537, key_size=2048)
        pem = made.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                 serialization.NoEncryption())
        descriptor = os.open(file, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        with os.fdopen(descriptor, "wb") as out:
            out.write(pem)
    key = serialization.load_pem_private_key(file.read_bytes(), password=None)
    if not isinstance(key, rsa.RSAPrivateKey):
        raise ValueError("the tool's key must be an RSA private key (openssl genrsa 2048)")
    return key


def tool_key():
    """The tool's RSA private key: DL_LTI_KEY_FILE, or lti-tool-key.pem made once in the data directory."""
    from assignments.db import DATA_ENV, ROOT

    path = os.environ.get(KEY_ENV) or str(Path(os.environ.get(DATA_ENV) or ROOT / "data") / "lti-tool-key.pem")
    return _tool_key(path)


def tool_jwk() -> dict:
    """The tool's public key as a JWK, its ``kid`` the key's RFC 7638 thumbprint."""
    from jwcrypto import jwk

    public = jwk.JWK.from_pyca(tool_key().public_key())
    return {**json.loads(public.export_public()), "kid": public.thumbprint(), "alg": "RS256", "use": "sig"}
