"""An LMS for the tests: the ``lti1p3platform`` package's platform (its OIDC login, its signed id_tokens,
its access tokens, its deep-linking check), served on loopback by uvicorn in a thread.

    with LmsEmulator(tool_url) as lms:          # the platform's JWKS, token, AGS and deep-link URLs live
        url = lms.login_url("learner-7", LEARNER, resource_link="rl-1")   # what the LMS sends the browser to
        form = lms.authorize(query_of_tool_redirect)                       # the platform's signed answer
        lms.scores                                                         # what reached its AGS endpoint
"""
from __future__ import annotations

import html
import socket
import threading
import time
import typing as t
from urllib.parse import parse_qsl, urlsplit

import uvicorn
from cryptography.hazmat.primitives import serialization
from cryptography.hazmat.primitives.asymmetric import rsa
from lti1p3platform.ltiplatform import LTI1P3PlatformConfAbstract
from lti1p3platform.message_launch import LTIAdvantageMessageLaunchAbstract
from lti1p3platform.oidc_login import OIDCLoginAbstract
from lti1p3platform.registration import Registration
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response
from starlette.routing import Route

ISSUER, CLIENT_ID, DEPLOYMENT = "https://lms.test", "dl-client-1", "deployment-1"
LEARNER = ["http://purl.imsglobal.org/vocab/lis/v2/membership#Learner"]
INSTRUCTOR = ["http://purl.imsglobal.org/vocab/lis/v2/membership#Instructor"]
# a student whose institution calls them an instructor elsewhere: a learner in this course
LEARNER_WITH_INSTITUTION_ROLE = LEARNER + ["http://purl.imsglobal.org/vocab/lis/v2/institution/person#Instructor"]
SCORE_SCOPE = "https://purl.imsglobal.org/spec/lti-ags/scope/score"
MEMBERSHIP_SCOPE = "https://purl.imsglobal.org/spec/lti-nrps/scope/contextmembership.readonly"


def _pem_pair() -> tuple[str, str]:
    key = rsa.generate_private_key(public_exponent=65537, key_size=2048)
    private = key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8,
                                serialization.NoEncryption()).decode()
    public = key.public_key().public_bytes(serialization.Encoding.PEM,
                                           serialization.PublicFormat.SubjectPublicKeyInfo).decode()
    return private, public


class _Config(LTI1P3PlatformConfAbstract):
    def init_platform_config(self, **kwargs: t.Any) -> None:
        self._registration = kwargs["registration"]

    def get_registration_by_params(self, **kwargs: t.Any) -> Registration:
        return self._registration


class _Login(OIDCLoginAbstract):
    def set_lti_message_hint(self, **kwargs: t.Any) -> None:
        self._lti_message_hint = kwargs["hint"]

    def get_redirect(self, url: str) -> str:
        return url


class _Launch(LTIAdvantageMessageLaunchAbstract):
    def get_preflight_response(self) -> dict:
        return self._request

    def render_launch_form(self, launch_data: dict, **kwargs: t.Any) -> dict:
        return launch_data


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class LmsEmulator:
    """One platform registration, served on 127.0.0.1; each launch set up by ``login_url``."""

    def __init__(self, tool_url: str, tool_jwks: dict | None = None, host: str = "127.0.0.1"):
        self.port = _free_port()
        self.url = f"http://{host}:{self.port}"  # "localhost" makes it another site than a tool on 127.0.0.1
        self.private_key, self.public_key = _pem_pair()
        self.registration = (Registration().set_iss(ISSUER).set_client_id(CLIENT_ID).set_deployment_id(DEPLOYMENT)
                             .set_oidc_login_url(tool_url + "/lti/login").set_launch_url(tool_url + "/lti/launch")
                             .set_deeplink_launch_url(tool_url + "/lti/launch")
                             .set_platform_public_key(self.public_key).set_platform_private_key(self.private_key))
        if tool_jwks is not None:
            self.registration.set_tool_key_set(tool_jwks)
        else:
            self.registration.set_tool_key_set_url(tool_url + "/lti/jwks")
        self.pending: dict[str, dict] = {}  # lti_message_hint -> the launch it stands for
        self.scores: list[dict] = []
        self.deep_links: list[list[dict]] = []
        self.fail_next: list[int] = []  # statuses the AGS endpoint answers first (429, 503, ...)
        self.members: list[dict] = []  # the course roster its NRPS endpoint gives, two members a page
        self.server: uvicorn.Server | None = None

    # -- what the admin pastes into the tool's platform file
    def registration_entry(self) -> dict:
        return {"issuer": ISSUER, "client_id": CLIENT_ID, "auth_login_url": self.url + "/authorize",
                "auth_token_url": self.url + "/token", "key_set_url": self.url + "/jwks",
                "deployment_ids": [DEPLOYMENT], "frame_origins": [self.url]}

    # -- the LMS starting a launch
    def login_url(self, user: str, roles: list[str], resource_link: str = "rl-1", context: str = "course-1",
                  deep_link: bool = False, custom: dict | None = None, lineitem: str | None = None,
                  name: str = "", return_url: str | None = None) -> str:
        hint = f"hint-{len(self.pending)}"
        self.pending[hint] = {"user": user, "roles": roles, "resource_link": resource_link, "context": context,
                              "deep_link": deep_link, "custom": custom, "name": name,
                              "return_url": return_url or self.url + "/deep_link_return",
                              "lineitem": lineitem or f"{self.url}/lineitems/{resource_link}"}
        login = _Login(None, _Config(registration=self.registration))
        login.set_lti_message_hint(hint=hint)
        if deep_link:
            login.set_deeplinking_launch_url()
        return login.initiate_login(user)

    def authorize(self, query: dict, claims: dict | None = None, expires_in: int = 300) -> dict:
        """The platform's answer to the tool's authorization redirect: {id_token, state, launch_url}."""
        setup = self.pending[query["lti_message_hint"]]
        launch = _Launch(query, _Config(registration=self.registration))
        launch.set_user_data(setup["user"], setup["roles"], full_name=setup["name"] or None)
        launch.set_launch_context_claim(setup["context"], context_title="Dynamics 101")
        if setup["deep_link"]:
            launch.set_dl(setup["return_url"], title="Dynamics Lab", extra_data={"data": "dl-data-1"},
                          accept_types={"ltiResourceLink"})
        else:
            launch.set_resource_link_claim(setup["resource_link"], title="Week 9")
            launch.set_ags(self.url + "/lineitems", setup["lineitem"])
            launch.set_nrps(f"{self.url}/memberships/{setup['context']}")
            if setup["custom"]:
                launch.set_custom_parameters_claim(setup["custom"])
        if claims:
            launch.set_extra_claims(claims)
        launch.set_id_token_expiration(expires_in)
        launch._registration = self.registration
        launch.validate_preflight_response(query)
        data = launch.generate_launch_request()
        return {**data, "launch_url": query["redirect_uri"]}

    # -- the platform's own endpoints
    async def _jwks(self, request: Request) -> Response:
        return JSONResponse({"keys": self.registration.get_jwks()})

    async def _authorize(self, request: Request) -> Response:
        form = self.authorize(dict(request.query_params))
        fields = "".join(f"<input type='hidden' name='{k}' value='{html.escape(form[k])}'>" for k in ("id_token", "state"))
        return HTMLResponse(f"<form method='post' action='{html.escape(form['launch_url'])}'>{fields}</form>"
                            "<script>document.forms[0].submit()</script>")

    async def _token(self, request: Request) -> Response:
        config = _Config(registration=self.registration)
        config.get_registration()
        form = dict(await request.form())
        try:
            return JSONResponse(config.get_access_token(form))
        except Exception as error:  # noqa: BLE001 - the platform's refusal, as an LMS answers it
            return JSONResponse({"error": "invalid_client", "detail": str(error)}, status_code=400)

    async def _scores(self, request: Request) -> Response:
        if self.fail_next:
            status = self.fail_next.pop(0)
            return JSONResponse({"error": "busy"}, status_code=status, headers={"Retry-After": "0"})
        config = _Config(registration=self.registration)
        config.get_registration()
        token = request.headers.get("authorization", "").removeprefix("Bearer ")
        if request.headers.get("content-type") != "application/vnd.ims.lis.v1.score+json":
            return JSONResponse({"error": "content type"}, status_code=415)
        try:
            ok = config.validate_token(token, allowed_scopes=[SCORE_SCOPE])
        except Exception:  # noqa: BLE001
            ok = False
        if not ok:
            return JSONResponse({"error": "unauthorized"}, status_code=401)
        self.scores.append({"lineitem": request.path_params["item"], **(await request.json())})
        return JSONResponse({}, status_code=200)

    async def _memberships(self, request: Request) -> Response:
        config = _Config(registration=self.registration)
        config.get_registration()
        token = request.headers.get("authorization", "").removeprefix("Bearer ")
        try:
            ok = config.validate_token(token, allowed_scopes=[MEMBERSHIP_SCOPE])
        except Exception:  # noqa: BLE001
            ok = False
        if not ok:
            return JSONResponse({"error": "unauthorized"}, status_code=401)
        start = int(request.query_params.get("page", "0"))
        headers = {}
        if start + 2 < len(self.members):
            headers["Link"] = f'<{self.url}{request.url.path}?page={start + 2}>; rel="next"'
        return JSONResponse({"id": str(request.url), "context": {"id": request.path_params["context"]},
                             "members": self.members[start:start + 2]}, headers=headers)

    async def _deep_link_return(self, request: Request) -> Response:
        config = _Config(registration=self.registration)
        config.get_registration()
        items = config.validate_deeplinking_resp(dict(await request.form()))
        self.deep_links.append(items)
        return HTMLResponse("<p id='lms-got'>The LMS received: " + html.escape(items[0].get("title", "")) + "</p>")

    async def _course(self, request: Request) -> Response:
        """The LMS's course page: the tool in an iframe, started at the login URL it is given."""
        start = html.escape(request.query_params["start"])
        return HTMLResponse(f"<!doctype html><title>Dynamics 101</title><h1 style='font:16px sans-serif'>Dynamics 101 "
                            f"(LMS emulator)</h1><iframe name='tool' src='{start}' title='Dynamics Lab' "
                            "style='width:100%;height:90vh;border:1px solid #999'></iframe>")

    def app(self) -> Starlette:
        return Starlette(routes=[Route("/jwks", self._jwks), Route("/authorize", self._authorize),
                                 Route("/course", self._course),
                                 Route("/token", self._token, methods=["POST"]),
                                 Route("/lineitems/{item}/scores", self._scores, methods=["POST"]),
                                 Route("/memberships/{context}", self._memberships),
                                 Route("/deep_link_return", self._deep_link_return, methods=["POST"])])

    def __enter__(self) -> "LmsEmulator":
        self.server = uvicorn.Server(uvicorn.Config(self.app(), host="127.0.0.1", port=self.port, log_level="warning"))
        threading.Thread(target=self.server.run, daemon=True).start()
        deadline = time.monotonic() + 10
        while not self.server.started:
            if time.monotonic() > deadline:
                raise RuntimeError("the LMS emulator did not start")
            time.sleep(0.02)
        return self

    def __exit__(self, *exc) -> None:
        self.server.should_exit = True


def query_of(url: str) -> dict:
    return dict(parse_qsl(urlsplit(url).query))
