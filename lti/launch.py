"""An LTI 1.3 launch, checked as the 1EdTech Security Framework asks, and handed to the page.

1. The platform opens ``/lti/login`` (OIDC third-party login initiation). The tool answers with a
   redirect to the platform's authorization URL carrying a fresh ``nonce`` and a ``state`` sealed
   with the course secret (issuer, client id, nonce, ten minutes).
2. The platform form-posts an ``id_token`` and the ``state`` to ``/lti/launch``. ``verify`` checks
   the state's seal, the token's RS256 signature against the platform's JWKS, ``iss``, ``aud`` (and
   ``azp``), ``exp``/``iat``, the ``nonce`` (the state's, and never seen before: a replay is refused),
   the deployment id (one the admin registered), the LTI version and message type.
3. What the launch means (a student of this course, or its instructor) goes to the page as a sealed
   hand-off of two minutes in the URL, spent once: no cookie has to survive the LMS's iframe, where
   browsers block third-party cookies. The page keeps it in its Streamlit session.

The state is not also bound to a cookie (the iframe would lose it): a login started elsewhere can
complete only with the platform's own signed token for the user the platform signed in.
Every refusal is logged (``dynamics_lab.lti``) without the token, and said in plain words.
"""
from __future__ import annotations

import base64
import functools
import hashlib
import hmac
import logging
import secrets
from dataclasses import dataclass
from urllib.parse import urlencode

import jwt

from assignments import signing
from lti import platforms
from lti.platforms import Platform

log = logging.getLogger("dynamics_lab.lti")
CLAIM = "https://purl.imsglobal.org/spec/lti/claim/"
DL_CLAIM = "https://purl.imsglobal.org/spec/lti-dl/claim/"
AGS_CLAIM = "https://purl.imsglobal.org/spec/lti-ags/claim/endpoint"
NRPS_CLAIM = "https://purl.imsglobal.org/spec/lti-nrps/claim/namesroleservice"
# The type each claim this tool reads has in the LTI 1.3 specs (Core §5, Deep Linking §4.4, AGS §3.1,
# NRPS §3.6): a launch whose claim is of another type is refused before anything reads it.
CLAIM_TYPES = {
    **{CLAIM + name: dict for name in ("resource_link", "context", "tool_platform", "launch_presentation", "lis",
                                       "custom")},
    **{CLAIM + name: str for name in ("message_type", "version", "deployment_id", "target_link_uri")},
    CLAIM + "roles": list, DL_CLAIM + "deep_linking_settings": dict, AGS_CLAIM: dict, NRPS_CLAIM: dict,
    "sub": str, "nonce": str, "name": str, "given_name": str, "family_name": str, "email": str,
}
MESSAGES = ("LtiResourceLinkRequest", "LtiDeepLinkingRequest")
STAFF = ("Instructor", "TeachingAssistant", "Administrator")  # of the context (a Mentor is a parent or advisor)
STATE_SECONDS, HANDOFF_SECONDS, LEEWAY = 600, 120, 60


class Refused(ValueError):
    """A launch that is not accepted; ``str`` is what the person is told, ``why`` what the log says."""

    def __init__(self, said: str, why: str):
        super().__init__(said)
        self.why = why


AGAIN = "Open the activity again from your course's page in the LMS."


def refuse(why: str, said: str = "This launch from your course site could not be verified, so it was not accepted.") -> Refused:
    log.warning("LTI launch refused: %s", why)
    return Refused(f"{said} {AGAIN}", why)


def login_redirect(params: dict) -> str:
    """Step 1: the URL to send the browser to, for a login initiation's parameters."""
    issuer, hint = params.get("iss"), params.get("login_hint")
    platform = platforms.find(issuer, params.get("client_id"))
    if platform is None:
        raise refuse(f"login from an unregistered issuer/client {issuer!r}/{params.get('client_id')!r}",
                     "This course site is not registered with Dynamics Lab (ask the admin to add it).")
    if not hint:
        raise refuse("login without login_hint")
    deployment = params.get("lti_deployment_id")
    if deployment and deployment not in platform.deployment_ids:
        raise refuse(f"login for unknown deployment {deployment!r} of {issuer}",
                     "This course site's deployment of Dynamics Lab is not registered (ask the admin to add it).")
    target = params.get("target_link_uri")
    if target and not str(target).startswith(platforms.public_url() + "/"):
        raise refuse(f"login for another tool's target_link_uri {str(target)[:200]!r}")
    nonce = secrets.token_urlsafe(24)
    state = signing.seal("lti-state", {"iss": platform.issuer, "aud": platform.client_id, "nonce": nonce},
                         STATE_SECONDS)
    query = {"scope": "openid", "response_type": "id_token", "response_mode": "form_post", "prompt": "none",
             "client_id": platform.client_id, "redirect_uri": platforms.public_url() + "/lti/launch",
             "login_hint": hint, "state": state, "nonce": nonce}
    if params.get("lti_message_hint"):
        query["lti_message_hint"] = params["lti_message_hint"]
    joiner = "&" if "?" in platform.auth_login_url else "?"
    return platform.auth_login_url + joiner + urlencode(query)


@functools.cache
def _jwks(url: str) -> jwt.PyJWKClient:
    return jwt.PyJWKClient(url, cache_keys=True, lifespan=3600, timeout=10)


@dataclass(frozen=True)
class Launch:
    platform: Platform
    claims: dict

    def claim(self, name: str, default=None):
        return self.claims.get(CLAIM + name, default)

    @property
    def message(self) -> str:
        return self.claim("message_type")

    @property
    def deployment(self) -> str:
        return self.claim("deployment_id")

    @property
    def context(self) -> dict:
        return self.claim("context") or {}

    @property
    def staff(self) -> bool:
        """An instructor or TA of this context. Only context roles count (``membership#Instructor`` or
        its short form): an institution role (``institution/person#Instructor``) does not make a
        student the instructor of their course."""
        for role in self.claim("roles") or []:
            if not isinstance(role, str):
                continue
            if role in STAFF or (role.startswith("http://purl.imsglobal.org/vocab/lis/v2/membership")
                                 and role.rsplit("#", 1)[-1] in STAFF):
                return True
        return False


def verify(form: dict, spend) -> Launch:
    """Step 2: the checked launch of a form post (``id_token``, ``state``). ``spend(key)`` records a
    one-time value and returns False if it was spent before (the database's ``lti_used``)."""
    token, state = form.get("id_token"), signing.unseal("lti-state", form.get("state"))
    if not isinstance(token, str) or not token:
        raise refuse("launch without id_token")
    if state is None:
        raise refuse("launch with a missing, altered or expired state",
                     "This launch took too long or was altered on its way, so it was not accepted.")
    platform = platforms.find(state["iss"], state["aud"])
    if platform is None:
        raise refuse(f"launch for a platform no longer registered: {state['iss']}")
    try:
        key = _jwks(platform.key_set_url).get_signing_key_from_jwt(token)
        claims = jwt.decode(token, key.key, algorithms=["RS256"], audience=platform.client_id,
                            issuer=platform.issuer, leeway=LEEWAY,
                            options={"require": ["exp", "iat", "iss", "aud", "sub", "nonce"]})
    except jwt.ExpiredSignatureError:
        raise refuse(f"expired id_token from {platform.issuer}", "This launch has expired.") from None
    except (jwt.PyJWKClientError, jwt.InvalidTokenError) as error:
        raise refuse(f"id_token from {platform.issuer} failed verification: {type(error).__name__}: {error}") from None
    wrong = [name for name, kind in CLAIM_TYPES.items() if name in claims and not isinstance(claims[name], kind)]
    if wrong:  # a platform's bug (a resource_link sent as a string): refused in words, never a 500
        raise refuse(f"id_token from {platform.issuer} with claims of the wrong type: {', '.join(wrong)}")
    audience = claims["aud"]
    if isinstance(audience, list) and len(audience) > 1 and claims.get("azp") != platform.client_id:
        raise refuse(f"id_token with several audiences and azp {claims.get('azp')!r}")
    if not hmac.compare_digest(str(claims["nonce"]), str(state["nonce"])):
        raise refuse("id_token nonce differs from the login's")
    launch = Launch(platform, claims)
    if launch.deployment not in platform.deployment_ids:
        raise refuse(f"unknown deployment {launch.deployment!r} of {platform.issuer}",
                     "This course site's deployment of Dynamics Lab is not registered (ask the admin to add it).")
    if launch.claim("version") != "1.3.0" or launch.message not in MESSAGES:
        raise refuse(f"unsupported message {launch.message!r} version {launch.claim('version')!r}")
    if launch.message == "LtiResourceLinkRequest" and not (launch.claim("resource_link") or {}).get("id"):
        raise refuse("resource link launch without resource_link.id")
    if not spend("nonce:" + hashlib.sha256(f"{platform.issuer}\x1f{claims['nonce']}".encode()).hexdigest()):
        raise refuse(f"replayed nonce from {platform.issuer}", "This launch was already used.")
    return launch


def label_of(issuer: str, sub: str) -> str:
    """The student's label here: opaque, fixed by the platform and its user id, keyed with the course
    secret (so it names nobody, and fits the gradebook's 40 characters)."""
    digest = hmac.new(signing._secret(), f"dynamics-lab/lti-user/v1\x1f{issuer}\x1f{sub}".encode(),
                      hashlib.sha256).digest()
    return "lti-" + base64.b32encode(digest[:15]).decode().lower()


def handoff(payload: dict) -> str:
    return signing.seal("lti-handoff", {**payload, "jti": secrets.token_urlsafe(12)}, HANDOFF_SECONDS)


def redeem(token: object, spend) -> dict | None:
    """The hand-off's payload, once: None when altered, expired or already spent."""
    payload = signing.unseal("lti-handoff", token)
    if payload is None or not spend("handoff:" + str(payload.get("jti"))):
        log.warning("LTI hand-off refused (altered, expired or reused)")
        return None
    return payload
